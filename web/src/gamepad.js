// The browser's gamepad, read as the protocol's `gamepad` message wants it: the W3C standard
// mapping's first 4 axes and 17 buttons (docs/gamepad.md). The server applies the dead zone and
// the map of Remark 5.7; the console only reads and forwards.

/** @typedef {import('./protocol').GamepadReading} GamepadReading */
/** @typedef {import('./protocol').GamepadInput} GamepadInput */

/**
 * What the console reads from a pad: Gamepad's fields, or a test's stand-in whose buttons may be
 * plain numbers.
 * @typedef {{ id?: string, mapping: string, connected?: boolean,
 *   axes: readonly number[], buttons: readonly (GamepadButton | number)[] }} PadLike
 */

export const AXIS_COUNT = 4;
export const BUTTON_COUNT = 17;
// The server's dead zone (`[operator] dead_zone`, docs/gamepad.md): |axis| below it reads 0.
export const DEAD_ZONE = 0.1;

// An axis as the server's map reads it (mobility::apply_dead_zone): 0 inside the dead zone, then
// rescaled to reach ±1 at full deflection, continuous at its edge.
/** @param {number} value  in [−1, 1] */
export function applyDeadZone(value) {
  const magnitude = Math.abs(value);
  if (!(magnitude > DEAD_ZONE)) return 0;  // its edge too (no −0), and NaN
  return Math.sign(value) * Math.min(1, (magnitude - DEAD_ZONE) / (1 - DEAD_ZONE));
}

/** @returns {GamepadReading} */
export function neutralReading() {
  return { axes: new Array(AXIS_COUNT).fill(0), buttons: new Array(BUTTON_COUNT).fill(false) };
}

// A pad's axes can overshoot ±1 by rounding; the server rejects anything beyond, so clamp. A
// non-finite axis is a broken reading: send it as centered rather than let the stick run away.
/** @param {number} value */
function cleanAxis(value) {
  if (!Number.isFinite(value)) return 0;
  return Math.max(-1, Math.min(1, value));
}

// The first connected pad in the standard mapping, or null. Pads in another mapping have axes
// and buttons in vendor order, which the server's map would misread.
/**
 * @template {PadLike} P
 * @param {readonly (P | null)[] | null | undefined} pads
 * @returns {P | null}
 */
export function firstStandardPad(pads) {
  for (const pad of pads ?? []) {
    if (pad && pad.connected !== false && pad.mapping === 'standard') return pad;
  }
  return null;
}

/**
 * @param {PadLike} pad
 * @returns {GamepadReading}
 */
export function readPad(pad) {
  const reading = neutralReading();
  for (let i = 0; i < AXIS_COUNT && i < pad.axes.length; ++i) reading.axes[i] = cleanAxis(pad.axes[i]);
  for (let i = 0; i < BUTTON_COUNT && i < pad.buttons.length; ++i) {
    const button = pad.buttons[i];
    reading.buttons[i] = typeof button === 'object' ? Boolean(button.pressed) : button > 0.5;
  }
  return reading;
}

// Polls navigator.getGamepads(); returns {pad, reading} or null when no standard pad is there.
/**
 * @param {{ getGamepads?: () => (Gamepad | null)[] }} nav
 * @returns {{ pad: Gamepad, reading: GamepadReading } | null}
 */
export function pollGamepad(nav = navigator) {
  if (typeof nav.getGamepads !== 'function') return null;
  const pad = firstStandardPad(Array.from(nav.getGamepads()));
  return pad ? { pad, reading: readPad(pad) } : null;
}

// The gamepad and the keyboard together: a key's axis wins where it is deflected, buttons add.
/**
 * @param {GamepadReading | null} pad
 * @param {GamepadReading} keys
 * @returns {GamepadReading}
 */
export function mergeReadings(pad, keys) {
  if (!pad) return keys;
  return {
    axes: pad.axes.map((value, i) => (keys.axes[i] !== 0 ? keys.axes[i] : value)),
    buttons: pad.buttons.map((pressed, i) => pressed || keys.buttons[i]),
  };
}

/**
 * @param {GamepadReading} reading
 * @returns {GamepadInput}
 */
export function gamepadMessage(reading) {
  return { type: 'gamepad', axes: reading.axes.slice(), buttons: reading.buttons.slice() };
}
