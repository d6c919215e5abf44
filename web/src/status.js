// The status window of Figure 8.1 and the rest of the driver's status (status_json.cpp): the
// line of mission time, cycle time, U (Ū), slope and yaw rate, the table of the eight motors,
// and the facts that explain what the rover does (mode, D, gait, faults, warnings).

import { element } from './dom.js';

/** @typedef {import('./protocol').Status} Status */
/** @typedef {import('./protocol').MotorStatus} MotorStatus */
/** @typedef {import('./protocol').MotorName} MotorName */
/** @typedef {import('./protocol').Velocities} Velocities */
/** @typedef {import('./protocol').StatusNumber} StatusNumber */

/** @type {MotorName[]} */
export const MOTORS = ['FL', 'FR', 'CL', 'CR', 'BL', 'BR', 'AF', 'AR'];

/** @typedef {'pos' | 'vel' | 'load' | 'τ' | 'duty' | 'cmd' | 'hold'} RowKey */

/** @type {[RowKey, string, (m: MotorStatus) => StatusNumber][]} */
const ROWS = [
  ['pos', 'position p [rad]', (m) => m.position_rad],
  ['vel', 'velocity w [rad/s]', (m) => m.velocity_radps],
  ['load', 'load l = w − ν [rad/s]', (m) => m.load_radps],
  ['τ', 'torque τ = l/B±(d) of (4.6) [N·m]', (m) => m.torque_nm],
  ['duty', 'duty cycle d', (m) => m.duty],
  ['cmd', 'commanded ŵ [rad/s]', (m) => m.commanded_radps],
  ['hold', "the slope hold's share of ŵ [rad/s]", (m) => m.slope_hold_radps],
];

const DEG_PER_RAD = 180 / Math.PI;

/**
 * @param {unknown} value
 * @param {number} [digits]
 */
export function fixed(value, digits = 3) {
  return typeof value === 'number' && Number.isFinite(value) ? value.toFixed(digits) : '–';
}

// value·factor, or null for a missing number: the status sends a non-finite one as null, which
// arithmetic would turn into 0.
/**
 * @param {StatusNumber | undefined} value
 * @param {number} factor
 */
function times(value, factor) {
  return typeof value === 'number' ? value * factor : null;
}

/**
 * @param {unknown} value
 * @param {number} digits
 */
function signed(value, digits) {
  const text = fixed(value, digits);
  return typeof value === 'number' && value >= 0 ? '+' + text : text;
}

// µ8's 16-character display as the firmware shows it (sensor_controller.hpp): the driver's eight
// characters (lcd.hpp: a code and the slope σ in degrees, e.g. "TO -2.5d"), then the supply
// voltage as "%7.2fV". The console has the driver's U, not µ8's own conversion of vcc; both come
// from the same reading.
/**
 * @param {unknown} lcd
 * @param {unknown} supplyV
 */
export function lcdDisplay(lcd, supplyV) {
  const text = (typeof lcd === 'string' ? lcd : '').padEnd(8).slice(0, 8);
  const volts = typeof supplyV === 'number' && Number.isFinite(supplyV) ? supplyV.toFixed(2) : '–';
  return `${text}${volts.padStart(7)}V`;
}

// 47:12.037 (minutes:seconds.milliseconds), with hours once the mission is that long.
/** @param {unknown} seconds */
export function missionTime(seconds) {
  if (typeof seconds !== 'number' || !Number.isFinite(seconds)) return '–';
  const ms = Math.floor(seconds * 1000);
  const h = Math.floor(ms / 3600000);
  const m = Math.floor(ms / 60000) % 60;
  const s = Math.floor(ms / 1000) % 60;
  const pad = (/** @type {number} */ n, /** @type {number} */ w) => String(n).padStart(w, '0');
  const clock = `${pad(m, 2)}:${pad(s, 2)}.${pad(ms % 1000, 3)}`;
  return h > 0 ? `${h}:${clock}` : clock;
}

/** @param {Velocities | undefined} v */
function velocities(v) {
  if (!v) return '–';
  return `v1 ${fixed(v.v1_radps, 2)} v2 ${fixed(v.v2_radps, 2)} v3 ${fixed(v.v3_radps, 2)} ` +
    `v4 ${fixed(v.v4_radps, 2)} ` +
    `v6 ${fixed(v.v6_radps, 2)} v7 ${fixed(v.v7_radps, 2)} rad/s`;
}

/**
 * @param {HTMLElement} list
 * @param {string[]} items
 * @param {string} emptyText
 */
function fillList(list, items, emptyText) {
  list.replaceChildren(...(items.length ? items : [emptyText]).map((text) => {
    const li = document.createElement('li');
    li.textContent = text;
    return li;
  }));
  list.classList.toggle('empty', items.length === 0);
}

export class StatusPanel {
  /** @param {ParentNode} root */
  constructor(root) {
    this.el = (/** @type {string} */ id) => element(root, id, HTMLElement);
    const table = element(root, 'motor-table', HTMLTableElement);
    const head = table.rows[0];
    for (const name of MOTORS) {
      const th = document.createElement('th');
      th.textContent = name;
      head.appendChild(th);
    }
    /** @type {Partial<Record<RowKey, HTMLTableCellElement[]>>} */
    this.cells = {};
    for (const [key, title] of ROWS) {
      const row = table.tBodies[0].insertRow();
      const th = document.createElement('th');
      th.textContent = key;
      th.title = title;
      row.appendChild(th);
      this.cells[key] = MOTORS.map(() => row.insertCell());
    }
  }

  /** @param {Partial<Status>} s */
  update(s) {
    const set = (/** @type {string} */ id, /** @type {string} */ text) => {
      this.el(id).textContent = text;
    };
    set('st-mission', missionTime(s.mission_time_s));
    set('st-cycle', `${fixed(times(s.cycle_time_s, 1000), 1)} ms`);
    set('st-voltage', `${fixed(s.supply_v, 1)} (${fixed(s.reference_supply_v, 1)}) V`);
    set('st-slope', `${signed(times(s.slope_rad, DEG_PER_RAD), 1)}°`);
    set('st-yaw', `${signed(times(s.yaw_rate_radps, DEG_PER_RAD), 1)}°/s`);
    set('st-lcd', lcdDisplay(s.lcd, s.supply_v));

    for (const [key, , pick] of ROWS) {
      const cells = this.cells[key] ?? [];
      MOTORS.forEach((name, i) => {
        const motor = s.motors?.[name];
        const cell = cells[i];
        cell.textContent = motor ? fixed(pick(motor)) : '–';
        if (key === 'pos') cell.classList.toggle('silent', (motor?.silent_cycles ?? 0) > 0);
      });
    }

    const phase = s.mode === 'startup' ? ` (${s.startup_phase})` : '';
    set('st-mode', `${s.mode ?? '–'}${phase}`);
    this.el('st-mode').dataset.mode = s.mode ?? '';
    set('st-max-duty', fixed(s.max_duty, 3));
    set('st-scales', `${fixed(s.driving_scale, 3)} / ${fixed(s.walking_scale, 3)}`);
    const g = s.gait;
    set('st-gait', g?.id && g.id !== 'none'
      ? `${g.name} · state ${g.state} · s ${fixed(g.speed, 2)}` : 'none');
    set('st-tilts', `${signed(times(s.front_tilt_rad, DEG_PER_RAD), 1)}° / ` +
      `${signed(times(s.rear_tilt_rad, DEG_PER_RAD), 1)}°`);
    set('st-targets', velocities(s.targets));
    set('st-commands', velocities(s.commands));
    const operator = [];
    if (s.operator_timeout) operator.push('no input for 0.5 s: targets zero');
    if (s.operator_rejection) operator.push(`rejected: ${s.operator_rejection}`);
    set('st-operator', operator.length ? operator.join(' · ') : 'ok');
    const bus = s.bus;
    set('st-bus', `${bus?.frames ?? '–'} frames, ${bus?.malformed ?? 0} malformed, ` +
      `${bus?.missed ?? 0} missed${bus?.last_error ? ' · ' + bus.last_error : ''}`);
    fillList(this.el('st-faults'), (s.faults ?? []).map((f) => `fault: ${f}`), 'no faults');
    fillList(this.el('st-warnings'), (s.warnings ?? []).map((w) => `warning: ${w}`), 'no warnings');
  }
}
