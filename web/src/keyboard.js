// The keyboard as a synthetic standard-layout gamepad, so that the server's map of Remark 5.7
// (docs/gamepad.md) applies unchanged. Keys are physical positions (KeyboardEvent.code), so the
// map is the same on every layout. Space is STOP (except in a text field: isTextEntry), handled by the
// caller (onStop).

import { neutralReading } from './gamepad.js';

/** @typedef {import('./protocol').GamepadReading} GamepadReading */

const LEFT_X = 0, LEFT_Y = 1, RIGHT_X = 2, RIGHT_Y = 3;

// code → [axis, direction]
/** @type {Record<string, [number, number]>} */
const AXIS_KEYS = {
  KeyW: [LEFT_Y, -1],     // stick up = forward
  KeyS: [LEFT_Y, +1],
  KeyA: [LEFT_X, -1],     // stick left = spin counter-clockwise
  KeyD: [LEFT_X, +1],
  ArrowUp: [RIGHT_Y, -1], // gait forward
  ArrowDown: [RIGHT_Y, +1],
  ArrowLeft: [RIGHT_X, -1],
  ArrowRight: [RIGHT_X, +1], // trench: front-right wheel forward
};

// code → standard-mapping button index
/** @type {Record<string, number>} */
const BUTTON_KEYS = {
  KeyQ: 4,     // LB: contract the front joint
  KeyZ: 6,     // LT: extend the front joint
  KeyE: 5,     // RB: contract the rear joint
  KeyC: 7,     // RT: extend the rear joint
  KeyR: 2,     // X: sideways drift m3, v3 > 0 (left-rear and right-front wheels forward)
  KeyF: 0,     // A: sideways drift m3, v3 < 0
  Digit1: 12,  // d-pad up: rolking
  Digit2: 15,  // d-pad right: front-wheel walking
  Digit3: 14,  // d-pad left: rear-wheel walking
  Digit4: 13,  // d-pad down: worm-like
  Digit5: 3,   // Y: rolking with extended base
  Digit0: 1,   // B: no gait
  KeyP: 8,     // back: calibration mode on/off
};

const HALF_DEFLECTION = 0.5;

export const KEY_MAP_CODES = [...Object.keys(AXIS_KEYS), ...Object.keys(BUTTON_KEYS)];

// The reading for a set of held key codes.
/**
 * @param {Iterable<string>} held KeyboardEvent.code of each key held
 * @param {boolean} shift
 * @returns {GamepadReading}
 */
export function keyboardReading(held, shift) {
  const reading = neutralReading();
  const scale = shift ? HALF_DEFLECTION : 1;
  for (const code of held) {
    if (code in AXIS_KEYS) {
      const [axis, direction] = AXIS_KEYS[code];
      reading.axes[axis] += direction * scale;
    } else if (code in BUTTON_KEYS) {
      reading.buttons[BUTTON_KEYS[code]] = true;
    }
  }
  // W and S together cancel, like a stick cannot point both ways.
  reading.axes = reading.axes.map((v) => Math.max(-1, Math.min(1, v)));
  return reading;
}

/** @param {EventTarget | null} target */
function isFormField(target) {
  return target instanceof HTMLElement &&
    (target.isContentEditable || ['INPUT', 'SELECT', 'TEXTAREA'].includes(target.tagName));
}

// A field that takes text, where the space bar types a space (the mission form's waypoints,
// "2,0; 2,2"); everywhere else it is STOP.
/** @param {EventTarget | null} target */
export function isTextEntry(target) {
  if (!(target instanceof HTMLElement)) return false;
  if (target.isContentEditable || target.tagName === 'TEXTAREA') return true;
  return target instanceof HTMLInputElement && ['text', 'search'].includes(target.type);
}

export class Keyboard {
  /**
   * @param {Window} target
   * @param {{ onStop: () => void }} handlers
   */
  constructor(target, { onStop }) {
    /** @type {Set<string>} */
    this.held = new Set();
    this.shift = false;
    target.addEventListener('keydown', (e) => this.down(e, onStop), true);
    target.addEventListener('keyup', (e) => this.up(e), true);
    // A key released while the window had no focus never sends keyup: forget them all, or the
    // rover would keep driving on a key nobody holds.
    target.addEventListener('blur', () => this.clear());
    document.addEventListener('visibilitychange', () => this.clear());
  }

  /**
   * @param {KeyboardEvent} event
   * @param {() => void} onStop
   */
  down(event, onStop) {
    if (event.code === 'Space' && !isTextEntry(event.target)) {
      // STOP, also with the focus on a button (whose own activation by space is cancelled).
      event.preventDefault();
      if (!event.repeat) onStop();
      return;
    }
    this.shift = event.shiftKey;
    if (event.ctrlKey || event.metaKey || event.altKey || isFormField(event.target)) return;
    if (event.code in AXIS_KEYS || event.code in BUTTON_KEYS) {
      event.preventDefault();
      this.held.add(event.code);
    }
  }

  /** @param {KeyboardEvent} event */
  up(event) {
    if (event.code === 'Space' && !isTextEntry(event.target)) {
      event.preventDefault();
      return;
    }
    this.shift = event.shiftKey;
    this.held.delete(event.code);
  }

  clear() {
    this.held.clear();
    this.shift = false;
  }

  get active() {
    return this.held.size > 0;
  }

  reading() {
    return keyboardReading(this.held, this.shift);
  }
}
