// The run-time settings the link accepts (`configure`, RuntimeSettings): Υ, the load
// distribution, chapter 6's behaviours and the speed scale. The status does not echo them, so the
// form starts "unchanged" everywhere and sends only what the operator set: a key left out of
// `configure` leaves that setting as it is.

import { control, element } from './dom.js';

/** @typedef {import('./protocol').ConfigureMessage} ConfigureMessage */
/** @typedef {import('./protocol').BehaviourName} BehaviourName */
/** @typedef {import('./protocol').LoadDistribution} LoadDistribution */

/**
 * The form's fields as FormData gives them: "" where the operator left a field unchanged.
 * @typedef {Record<string, string>} FormValues
 */

/** @type {BehaviourName[]} */
export const BEHAVIOURS = ['power_management', 'slant_response', 'contract_on_turn', 'axle_placement'];
/** @type {readonly string[]} */
const LOAD_DISTRIBUTIONS = ['off', 'v', 's'];

/**
 * @param {string} value
 * @returns {value is LoadDistribution}
 */
function isLoadDistribution(value) {
  return LOAD_DISTRIBUTIONS.includes(value);
}

// The `configure` message for the form's values, or {error} naming the field that is wrong.
/**
 * @param {FormValues} values
 * @returns {{ message: ConfigureMessage, error?: undefined } | { error: string, message?: undefined }}
 */
export function configureMessage(values) {
  /** @type {ConfigureMessage} */
  const message = { type: 'configure' };
  if (values.max_drop_v !== '') {
    const v = Number(values.max_drop_v);
    if (!(v > 0 && v <= 10)) return { error: `Υ: ${values.max_drop_v} is out of range; allowed (0, 10] V` };
    message.max_drop_v = v;
  }
  if (values.load_distribution !== '') {
    if (!isLoadDistribution(values.load_distribution)) {
      return { error: `load distribution: ${values.load_distribution} is not one of off, v, s` };
    }
    message.load_distribution = values.load_distribution;
  }
  /** @type {Partial<Record<BehaviourName, boolean>>} */
  const behaviours = {};
  for (const name of BEHAVIOURS) {
    if (values[name] === 'on' || values[name] === 'off') behaviours[name] = values[name] === 'on';
  }
  if (Object.keys(behaviours).length) message.behaviours = behaviours;
  if (values.speed_scale !== '') {
    const s = Number(values.speed_scale);
    if (!(s >= 0 && s <= 1)) return { error: `speed scale: ${values.speed_scale} is out of range; allowed 0..1` };
    message.speed_scale = s;
  }
  return { message };
}

export class ConfigPanel {
  /**
   * @param {HTMLFormElement} form
   * @param {{ send: (message: ConfigureMessage) => boolean, clearFaults: () => void }} actions
   */
  constructor(form, { send, clearFaults }) {
    this.form = form;
    for (const name of BEHAVIOURS) {
      control(form, name, HTMLSelectElement).replaceChildren(...[['', 'unchanged'], ['on', 'on'], ['off', 'off']]
        .map(([value, text]) => new Option(text, value)));
    }
    this.result = element(form, 'config-result', HTMLElement);
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      /** @type {FormValues} */
      const values = {};
      for (const [name, value] of new FormData(form)) values[name] = String(value);
      const { message, error } = configureMessage(values);
      if (!message) {
        this.result.textContent = error;
        return;
      }
      const { type, ...settings } = message;
      const sent = send(message);
      this.result.textContent = !sent ? 'not sent: no connection'
        : Object.keys(settings).length ? `sent ${JSON.stringify(settings)}` : 'nothing to change';
    });
    element(form, 'clear-faults', HTMLElement).addEventListener('click', () => clearFaults());
  }

  // The server accepts `configure` and `clear_faults` only from the controlling console.
  /** @param {boolean} enabled */
  setEnabled(enabled) {
    for (const field of this.form.elements) {
      if (field instanceof HTMLInputElement || field instanceof HTMLSelectElement ||
          field instanceof HTMLButtonElement || field instanceof HTMLFieldSetElement) {
        field.disabled = !enabled;
      }
    }
    this.form.title = enabled ? '' : 'take control to change the configuration';
  }
}
