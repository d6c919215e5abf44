// The page's elements, looked up with the type the code needs: a missing or different element is
// an error that names it, not a null that fails later.

/**
 * @template {Element} T
 * @typedef {{ new (): T, prototype: T, name: string }} ElementType
 */

/**
 * The element with this id under `root`.
 * @template {Element} T
 * @param {ParentNode} root
 * @param {string} id
 * @param {ElementType<T>} type
 * @returns {T}
 */
export function element(root, id, type) {
  const found = root.querySelector(`#${id}`);
  if (!(found instanceof type)) throw new Error(`the page has no ${type.name} #${id}`);
  return found;
}

/**
 * The form's control named `name`.
 * @template {Element} T
 * @param {HTMLFormElement} form
 * @param {string} name
 * @param {ElementType<T>} type
 * @returns {T}
 */
export function control(form, name, type) {
  const found = form.elements.namedItem(name);
  if (!(found instanceof type)) throw new Error(`the form has no ${type.name} named ${name}`);
  return found;
}
