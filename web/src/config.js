// The run-time settings the link accepts (`configure`, RuntimeSettings): Υ, the load
// distribution, chapter 6's behaviours and the speed scale. The status does not echo them, so the
// form starts "unchanged" everywhere and sends only what the operator set: a key left out of
// `configure` leaves that setting as it is.

export const BEHAVIOURS = ['power_management', 'slant_response', 'contract_on_turn', 'axle_placement'];

// The `configure` message for the form's values, or {error} naming the field that is wrong.
export function configureMessage(values) {
  const message = { type: 'configure' };
  if (values.max_drop_v !== '') {
    const v = Number(values.max_drop_v);
    if (!(v > 0 && v <= 10)) return { error: `Υ: ${values.max_drop_v} is out of range; allowed (0, 10] V` };
    message.max_drop_v = v;
  }
  if (values.load_distribution !== '') message.load_distribution = values.load_distribution;
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
  constructor(form, { send, clearFaults }) {
    this.form = form;
    for (const name of BEHAVIOURS) {
      form.elements[name].replaceChildren(...[['', 'unchanged'], ['on', 'on'], ['off', 'off']]
        .map(([value, text]) => new Option(text, value)));
    }
    this.result = form.querySelector('#config-result');
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      const values = Object.fromEntries(new FormData(form).entries());
      const { message, error } = configureMessage(values);
      if (error) {
        this.result.textContent = error;
        return;
      }
      const { type, ...settings } = message;
      const sent = send(message);
      this.result.textContent = !sent ? 'not sent: no connection'
        : Object.keys(settings).length ? `sent ${JSON.stringify(settings)}` : 'nothing to change';
    });
    form.querySelector('#clear-faults').addEventListener('click', () => clearFaults());
  }

  // The server accepts `configure` and `clear_faults` only from the controlling console.
  setEnabled(enabled) {
    for (const element of this.form.elements) element.disabled = !enabled;
    this.form.title = enabled ? '' : 'take control to change the configuration';
  }
}
