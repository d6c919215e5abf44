// Velocity mode: driving by cmd_vel (docs/operator-protocol.md, `velocity`), as a ROS operator
// drives with teleop_twist. While it is on and the console holds control, the left stick (or W A
// S D, the same axes as docs/gamepad.md's m1/m2) becomes `velocity` messages at the console's
// input rate — forward axis × the server's largest speed, turn axis × its largest yaw rate, after
// the gamepad's dead zone — instead of the gamepad reading; centred, it sends zero velocity. The
// form keeps a constant velocity going (re-sent every tick, so the 0.5 s operator timeout does not
// end it) until "stop", a pushed stick, STOP, or the mode goes off. The limits come from the
// server's hello (velocity_limits); a server that does not tell them gets no velocity mode.

import { control, element } from './dom.js';
import { applyDeadZone } from './gamepad.js';
import { checkedNumber } from './mission.js';

/** @typedef {import('./protocol').GamepadReading} GamepadReading */
/** @typedef {import('./protocol').VelocityLimits} VelocityLimits */
/** @typedef {import('./protocol').VelocityInput} VelocityInput */
/** @typedef {import('./protocol').HeartbeatInput} HeartbeatInput */
/** @typedef {{ v_mps: number, yaw_radps: number }} VelocityCommand */

const LEFT_X = 0, LEFT_Y = 1;

/**
 * The hello's velocity_limits, or null when they are missing or not positive finite numbers.
 * @param {unknown} value
 * @returns {VelocityLimits | null}
 */
export function velocityLimits(value) {
  if (typeof value !== 'object' || value === null) return null;
  const { v_mps: v, yaw_radps: yaw } = /** @type {Record<string, unknown>} */ (value);
  const positive = (/** @type {unknown} */ x) => typeof x === 'number' && Number.isFinite(x) && x > 0;
  return positive(v) && positive(yaw) ? { v_mps: /** @type {number} */ (v), yaw_radps: /** @type {number} */ (yaw) } : null;
}

/**
 * @param {number} value
 * @param {number} limit
 */
const clip = (value, limit) => Math.max(-limit, Math.min(limit, value));

/**
 * The left stick as cmd_vel: up = forward (v = −axis 1), left = counter-clockwise (ω = −axis 0),
 * each after the dead zone and × its limit; never beyond the limits (the server rejects that).
 * @param {GamepadReading} reading
 * @param {VelocityLimits} limits
 * @returns {VelocityCommand}
 */
export function stickVelocity(reading, limits) {
  // + 0 turns −0 into 0: the sent JSON and the shown text then read "0", not "-0".
  return {
    v_mps: clip(-applyDeadZone(reading.axes[LEFT_Y]) * limits.v_mps, limits.v_mps) + 0,
    yaw_radps: clip(-applyDeadZone(reading.axes[LEFT_X]) * limits.yaw_radps, limits.yaw_radps) + 0,
  };
}

/** @param {VelocityCommand} c */
const isZero = (c) => c.v_mps === 0 && c.yaw_radps === 0;

// A limit as the form's messages show it: rounded down, so a value within it is accepted.
/** @param {number} limit */
const shownLimit = (limit) => (Math.floor(limit * 1000) / 1000).toFixed(3);

/**
 * The form's velocity, or what is wrong with it. Each field a number within its limit; 0 is
 * allowed for one of them (straight or on the spot), not for both (that is "stop").
 * @param {string} vText  m/s, − backwards
 * @param {string} yawText  rad/s, + counter-clockwise
 * @param {VelocityLimits | null} limits
 * @returns {{ command: VelocityCommand, error?: undefined } | { error: string, command?: undefined }}
 */
export function formVelocity(vText, yawText, limits) {
  if (!limits) return { error: 'this server does not tell its velocity limits (hello.velocity_limits): no velocity mode' };
  const v = checkedNumber(vText, 'v', 'm/s', limits.v_mps, { zero: true, shownLimit: shownLimit(limits.v_mps) });
  if (v.value === undefined) return { error: v.error };
  const yaw = checkedNumber(yawText, 'ω', 'rad/s', limits.yaw_radps, { zero: true, shownLimit: shownLimit(limits.yaw_radps) });
  if (yaw.value === undefined) return { error: yaw.error };
  const command = { v_mps: v.value + 0, yaw_radps: yaw.value + 0 };
  if (isZero(command)) return { error: 'v and ω are both 0: that is "stop"' };
  return { command };
}

/**
 * What velocity mode sends this tick, and the form's velocity that holds after it:
 *   a stick pushed  → its velocity; it takes over and ends the form's velocity
 *   the form's      → the form's velocity, again
 *   a turn/move/goto running (drivingMission), nothing else → a heartbeat (a velocity, even 0,
 *                     would replace the mission)
 *   otherwise       → zero velocity: the driver stops the rover
 * @param {{ reading: GamepadReading, limits: VelocityLimits, held: VelocityCommand | null,
 *   drivingMission: boolean }} state
 * @returns {{ message: VelocityInput | HeartbeatInput, held: VelocityCommand | null,
 *   source: 'stick' | 'form' | 'mission' | 'neutral' }}
 */
export function velocityStep({ reading, limits, held, drivingMission }) {
  const stick = stickVelocity(reading, limits);
  /** @param {VelocityCommand} c */
  const velocity = (c) => /** @type {VelocityInput} */ ({ type: 'velocity', v_mps: c.v_mps, yaw_radps: c.yaw_radps });
  if (!isZero(stick)) return { message: velocity(stick), held: null, source: 'stick' };
  if (held) return { message: velocity(held), held, source: 'form' };
  if (drivingMission) return { message: { type: 'heartbeat' }, held: null, source: 'mission' };
  return { message: velocity(stick), held: null, source: 'neutral' };
}

// "v 0.100 m/s, ω −0.200 rad/s"
/** @param {VelocityCommand} c */
export function velocityText(c) {
  return `v ${c.v_mps.toFixed(3)} m/s, ω ${c.yaw_radps.toFixed(3)} rad/s`;
}

// The toggle and the form (index.html, #velocity-form); the sender (main.js) asks next() what to
// send each tick while the mode is on.
export class VelocityPanel {
  /**
   * @param {ParentNode} root
   * @param {{ send: (message: VelocityInput) => boolean }} actions  sends a message at once
   */
  constructor(root, { send }) {
    this.form = element(root, 'velocity-form', HTMLFormElement);
    this.toggle = control(this.form, 'velocity_mode', HTMLInputElement);
    this.vField = control(this.form, 'v_mps', HTMLInputElement);
    this.yawField = control(this.form, 'yaw_radps', HTMLInputElement);
    this.sendButton = element(root, 'velocity-send', HTMLButtonElement);
    this.stopButton = element(root, 'velocity-stop', HTMLButtonElement);
    this.result = element(root, 'velocity-result', HTMLElement);
    this.limitsText = element(root, 'velocity-limits', HTMLElement);
    /** @type {VelocityLimits | null} */
    this.limits = null;
    /** @type {VelocityCommand | null} the form's velocity, kept going */
    this.held = null;
    /** @type {VelocityCommand | null} the velocity sent last (null: none, or a heartbeat) */
    this.sent = null;
    this.inControl = false;
    this.toggle.checked = false;
    this.toggle.addEventListener('change', () => {
      this.held = null;
      this.sent = null;
      this.say(this.toggle.checked ? 'velocity mode on: the left stick / W A S D send velocity' : 'velocity mode off', false);
      this.refresh();
      // The keyboard ignores keys while the focus is in a form's control: W A S D drive at once.
      this.toggle.blur();
    });
    this.sendButton.addEventListener('click', () => {
      const { command, error } = formVelocity(this.vField.value, this.yawField.value, this.limits);
      if (!command) {
        this.say(error, true);
        return;
      }
      this.held = command;
      this.say(`sending ${velocityText(command)} until stop`, false);
    });
    this.stopButton.addEventListener('click', () => this.stop());
    this.form.addEventListener('submit', (event) => {
      event.preventDefault();
      if (!this.sendButton.disabled) this.sendButton.click();
    });
    this.send = send;
    this.refresh();
  }

  // The form's velocity ends; zero goes out at once rather than at the next tick.
  stop() {
    this.held = null;
    if (!this.active) return;
    const zero = { v_mps: 0, yaw_radps: 0 };
    const sent = this.send({ type: 'velocity', ...zero });
    if (sent) this.sent = zero;
    this.say(sent ? 'sent zero velocity' : 'not sent: no connection', !sent);
  }

  /** @param {unknown} value  the hello's velocity_limits */
  setLimits(value) {
    this.limits = velocityLimits(value);
    this.limitsText.textContent = this.limits
      ? `limits ±${this.limits.v_mps.toFixed(3)} m/s, ±${this.limits.yaw_radps.toFixed(3)} rad/s`
      : 'this server does not tell its velocity limits: no velocity mode';
    if (!this.limits) this.toggle.checked = false;
    this.refresh();
  }

  /** @param {boolean} inControl */
  setEnabled(inControl) {
    this.inControl = inControl;
    if (!inControl) this.held = null;
    this.refresh();
  }

  get enabled() {
    return this.toggle.checked && this.limits !== null;
  }

  // The mode acts: on, with limits, in control.
  get active() {
    return this.enabled && this.inControl;
  }

  refresh() {
    this.toggle.disabled = this.limits === null;
    const why = !this.inControl ? 'take control to drive by velocity'
      : !this.enabled ? 'switch velocity mode on first' : '';
    for (const button of [this.sendButton, this.stopButton]) {
      button.disabled = why !== '';
      button.title = why;
    }
  }

  /**
   * What to send this tick (velocityStep), remembering the form's velocity and what went out.
   * @param {GamepadReading} reading
   * @param {boolean} drivingMission
   */
  next(reading, drivingMission) {
    if (!this.limits) throw new Error('VelocityPanel.next without limits');
    const step = velocityStep({ reading, limits: this.limits, held: this.held, drivingMission });
    if (this.held && !step.held) this.say('the stick took over: the form\'s velocity ended', false);
    this.held = step.held;
    this.sent = step.message.type === 'velocity' ? { v_mps: step.message.v_mps, yaw_radps: step.message.yaw_radps } : null;
    return step;
  }

  // STOP (button, space bar, another console's): the form's velocity ends too.
  cancel() {
    this.held = null;
  }

  /**
   * @param {string} text
   * @param {boolean} bad
   */
  say(text, bad) {
    this.result.textContent = text;
    this.result.classList.toggle('bad', bad);
  }
}
