// The run-time settings the link accepts (`configure`, RuntimeSettings): Υ, the load
// distribution, chapter 6's behaviours, the speed scale and the supply (battery or tether). Every field starts at the setting in
// force, as the status reports it (`settings`: "off (in force)", a placeholder "1.5 (in force)"),
// and the form sends only what the operator changed: a key left out of `configure` leaves that
// setting as it is.

import { control, element } from './dom.js';

/** @typedef {import('./protocol').ConfigureMessage} ConfigureMessage */
/** @typedef {import('./protocol').BehaviourName} BehaviourName */
/** @typedef {import('./protocol').LoadDistribution} LoadDistribution */
/** @typedef {import('./protocol').RuntimeSettings} RuntimeSettings */

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
  if (values.supply !== undefined && values.supply !== '') {
    if (values.supply !== 'battery' && values.supply !== 'tether') {
      return { error: `supply: ${values.supply} is not one of battery, tether` };
    }
    message.supply = values.supply;
  }
  return { message };
}

/** @type {Record<LoadDistribution, string>} */
const LOAD_DISTRIBUTION_NAMES = { off: 'off', v: 'hᵛ (6.5)', s: 'hˢ (6.6)' };

// What each field shows as the setting in force ("unchanged" before the first status).
/**
 * @param {RuntimeSettings | null | undefined} settings
 * @returns {Record<string, string>}
 */
export function inForceLabels(settings) {
  /** @type {Record<string, string>} */
  const labels = {};
  const fields = ['max_drop_v', 'load_distribution', ...BEHAVIOURS, 'speed_scale', 'supply'];
  if (!settings) {
    for (const name of fields) labels[name] = 'unchanged';
    return labels;
  }
  labels.max_drop_v = `${settings.max_drop_v} (in force)`;
  labels.load_distribution = `${LOAD_DISTRIBUTION_NAMES[settings.load_distribution] ?? settings.load_distribution} (in force)`;
  for (const name of BEHAVIOURS) labels[name] = `${settings.behaviours[name] ? 'on' : 'off'} (in force)`;
  labels.speed_scale = `${settings.speed_scale} (in force)`;
  labels.supply = `${settings.supply} (in force)`;
  return labels;
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
    /** @type {string} */
    this.shown = '';
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

  // The settings in force (the status' `settings`): each field's "leave as it is" choice names
  // them. Redrawn only when they change, never touching what the operator has typed or chosen.
  /** @param {RuntimeSettings | null | undefined} settings */
  showSettings(settings) {
    const key = JSON.stringify(settings ?? null);
    if (key === this.shown) return;
    this.shown = key;
    for (const [name, text] of Object.entries(inForceLabels(settings))) {
      const field = this.form.elements.namedItem(name);
      if (field instanceof HTMLInputElement) {
        field.placeholder = text;
      } else if (field instanceof HTMLSelectElement && field.options[0]?.value === '') {
        field.options[0].text = text;
      }
    }
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
