// The mission form: turn by an angle, move a distance, go to waypoints (docs/operator-protocol.md,
// `mission`), Stop mission (`stop`), and the mission's status (status.mission). Controller only.
//
// A running mission needs operator input like the sticks do: the driver aborts it after 0.5 s
// without any. While one runs and the operator's reading is neutral the console sends
// `heartbeat` at 20 Hz instead of the neutral gamepad reading (inputToSend); a stick pushed sends
// the gamepad again, which takes over (the driver aborts the mission).

import { control, element } from './dom.js';
import { parseNumber, parseWaypoints, formatWaypoints } from './map.js';

/** @typedef {import('./protocol').MissionInput} MissionInput */
/** @typedef {import('./protocol').MissionStatus} MissionStatus */
/** @typedef {import('./protocol').Pose} Pose */
/** @typedef {import('./velocity.js').VelocityCommand} VelocityCommand */
/** @typedef {import('./map.js').Point} Point */

export const MAX_TURN_DEG = 720;  // two turns
export const MAX_MOVE_M = 100;
export const MAX_WAYPOINTS = 64;
export const WAYPOINT_LIMIT_M = 1000;
// A mission's own standing after each leg, 0 < settle_s ≤ 60 s (blank: the configured one).
export const MAX_SETTLE_S = 60;
// How long a mission just sent counts as running before the status shows it (statuses come at
// 20 Hz; a server without missions never shows it).
export const PENDING_MS = 1000;

const DEG_PER_RAD = 180 / Math.PI;

/**
 * @param {unknown} v
 * @returns {v is number}
 */
const finite = (v) => typeof v === 'number' && Number.isFinite(v);

/**
 * A number typed in a form field, or what is wrong with it.
 * @param {string} text
 * @param {string} what   for the message: "turn"
 * @param {string} unit   "°"
 * @param {number} limit  |value| ≤ limit
 * @param {{ zero?: boolean, shownLimit?: string }} [options]  zero: 0 is allowed (else "does
 *   nothing"); shownLimit: the limit as the message shows it (default: as it is)
 * @returns {{ value: number, error?: undefined } | { error: string, value?: undefined }}
 */
export function checkedNumber(text, what, unit, limit, { zero = false, shownLimit = String(limit) } = {}) {
  if (text.trim() === '') return { error: `${what}: empty; type a number in ${unit}` };
  const v = parseNumber(text);
  if (v === null) return { error: `${what}: "${text.trim()}" is not a number (${unit})` };
  if (Math.abs(v) > limit) return { error: `${what}: ${v} is out of range; allowed −${shownLimit}..${shownLimit} ${unit}` };
  if (v === 0 && !zero) return { error: `${what}: 0 ${unit} does nothing` };
  return { value: v };
}

/**
 * The mission message for the form's text, or what is wrong with it.
 *   turn: degrees, + counter-clockwise (sent in radians)
 *   move: metres, − backwards
 *   goto: "x,y; x,y" in metres, odometry frame
 *   standText: the standing after each leg in seconds, 0 < s ≤ 60; blank sends none (the
 *   configured navigation.settle_s)
 * @param {'turn' | 'move' | 'goto'} kind
 * @param {string} text
 * @param {string} [standText]
 * @returns {{ message: MissionInput, error?: undefined } | { error: string, message?: undefined }}
 */
export function missionMessage(kind, text, standText = '') {
  /** @type {{ settle_s?: number }} */
  const stand = {};
  if (standText.trim() !== '') {
    const v = parseNumber(standText);
    if (v === null) return { error: `stand: "${standText.trim()}" is not a number (s)` };
    if (!(v > 0 && v <= MAX_SETTLE_S)) {
      return { error: `stand: ${v} s is out of range; allowed 0 < s ≤ ${MAX_SETTLE_S} s (blank: the configured one)` };
    }
    stand.settle_s = v;
  }
  if (kind === 'turn') {
    const { value, error } = checkedNumber(text, 'turn', '°', MAX_TURN_DEG);
    if (value === undefined) return { error };
    return { message: { type: 'mission', kind: 'turn', angle_rad: value / DEG_PER_RAD, ...stand } };
  }
  if (kind === 'move') {
    const { value, error } = checkedNumber(text, 'move', 'm', MAX_MOVE_M);
    if (value === undefined) return { error };
    return { message: { type: 'mission', kind: 'move', distance_m: value, ...stand } };
  }
  const { waypoints, error } = parseWaypoints(text, { max: MAX_WAYPOINTS, limitM: WAYPOINT_LIMIT_M });
  if (!waypoints) return { error: `go to: ${error}` };
  return {
    message: { type: 'mission', kind: 'goto', waypoints: waypoints.map((p) => ({ x_m: p.x, y_m: p.y })), ...stand },
  };
}

/**
 * What the 20 Hz sender sends in tick `tick`: the gamepad reading, or — while a mission runs and
 * the reading is neutral (no STOP latched) — a heartbeat on every tick (20 Hz: ten chances inside
 * the driver's 0.5 s timeout, which a busy browser's timers can stretch).
 * @param {{ missionActive: boolean, neutral: boolean, stopLatched: boolean, tick: number }} state
 * @returns {'gamepad' | 'heartbeat' | 'nothing'}
 */
export function inputToSend({ missionActive, neutral, stopLatched, tick }) {
  void tick;
  if (!missionActive || !neutral || stopLatched) return 'gamepad';
  return 'heartbeat';
}

// Whether a turn, move or goto runs: the status says so, or one was sent within PENDING_MS and
// the status does not yet show a newer mission. A `velocity` mission does not count: it is the
// velocity stream itself (velocity.js), and a heartbeat would keep it going after its stream ended.
export class MissionWatch {
  constructor() {
    /** @type {number | null} */
    this.sentAt = null;
    this.sentAfterId = 0;
  }

  /**
   * A mission was sent at `now` [ms], while the status' newest mission was `lastId`.
   * @param {number} lastId
   * @param {number} now
   */
  sent(lastId, now) {
    this.sentAt = now;
    this.sentAfterId = lastId;
  }

  /**
   * @param {MissionStatus | undefined} mission
   * @param {number} now
   */
  active(mission, now) {
    if (this.sentAt !== null && (now - this.sentAt >= PENDING_MS || (mission && mission.id > this.sentAfterId))) {
      this.sentAt = null;  // shown, or never will be
    }
    return (mission?.state === 'running' && mission.kind !== 'velocity') || this.sentAt !== null;
  }

  cancel() {
    this.sentAt = null;
  }
}

/**
 * One line about the mission for people: "goto · running · leg 2 of 3 · 1.20 m to go". A running
 * velocity mission has no progress: its values instead, the ones this console sends (`sent`, when
 * it is the one sending) and the pose's speed and yaw rate (`pose`).
 * @param {MissionStatus | undefined} m
 * @param {{ sent?: VelocityCommand | null, pose?: Pose }} [velocity]
 */
export function missionSummary(m, { sent = null, pose } = {}) {
  if (!m) return 'no mission support in this server (the status has no mission)';
  if (m.kind === 'none' || m.id === 0) return 'no mission yet';
  const parts = [`#${m.id} ${m.kind}`, m.state];
  if (m.kind === 'velocity') {
    if (m.state !== 'running') return parts.join(' · ');
    if (sent) parts.push(`sent v ${sent.v_mps.toFixed(3)} m/s, ω ${sent.yaw_radps.toFixed(3)} rad/s`);
    if (pose && finite(pose.speed_mps) && finite(pose.yaw_rate_radps)) {
      parts.push(`estimated ${pose.speed_mps.toFixed(3)} m/s, ${pose.yaw_rate_radps.toFixed(3)} rad/s`);
    }
    return parts.join(' · ');
  }
  const points = Array.isArray(m.waypoints) ? m.waypoints.length : 0;
  if (m.kind === 'goto' && points > 0) parts.push(`leg ${Math.min(m.leg + 1, points)} of ${points}`);
  if (finite(m.progress)) parts.push(`${Math.round(m.progress * 100)} %`);
  if (m.state === 'running' && finite(m.remaining_m)) parts.push(`${m.remaining_m.toFixed(2)} m to go`);
  if (m.state === 'running' && finite(m.remaining_rad)) parts.push(`${(m.remaining_rad * DEG_PER_RAD).toFixed(1)}° to turn`);
  if (finite(m.corrections) && m.corrections > 0) parts.push(`${m.corrections} correction${m.corrections === 1 ? '' : 's'}`);
  if (m.state === 'running' && finite(m.settle_s) && m.settle_s > 0) parts.push(`stands ${m.settle_s} s a leg`);
  return parts.join(' · ');
}

export class MissionPanel {
  /**
   * @param {ParentNode} root
   * @param {{ send: (message: MissionInput) => boolean, stop: () => boolean,
   *   onDraft: (points: Point[]) => void }} actions
   */
  constructor(root, { send, stop, onDraft }) {
    this.form = element(root, 'mission-form', HTMLFormElement);
    this.result = element(root, 'mission-result', HTMLElement);
    this.summary = element(root, 'mission-summary', HTMLElement);
    this.progress = element(root, 'mission-progress', HTMLProgressElement);
    this.reason = element(root, 'mission-reason', HTMLElement);
    this.watch = new MissionWatch();
    /** @type {MissionStatus | undefined} */
    this.mission = undefined;
    this.gotoField = control(this.form, 'goto', HTMLInputElement);
    this.onDraft = onDraft;
    /** @type {Record<'turn' | 'move' | 'goto', HTMLInputElement>} */
    const fields = {
      turn: control(this.form, 'turn_deg', HTMLInputElement),
      move: control(this.form, 'move_m', HTMLInputElement),
      goto: this.gotoField,
    };
    const standField = control(this.form, 'settle_s', HTMLInputElement);
    for (const kind of /** @type {const} */ (['turn', 'move', 'goto'])) {
      element(root, `mission-${kind}`, HTMLButtonElement).addEventListener('click', () => {
        const { message, error } = missionMessage(kind, fields[kind].value, standField.value);
        if (!message) {
          this.say(error, true);
          return;
        }
        if (!send(message)) {
          this.say('not sent: no connection', true);
          return;
        }
        this.watch.sent(this.mission?.id ?? 0, performance.now());
        const { type, ...rest } = message;
        this.say(`sent ${type} ${JSON.stringify(rest)}`, false);
      });
    }
    // Enter in a field sends that field's mission.
    this.form.addEventListener('submit', (event) => {
      event.preventDefault();
      const field = document.activeElement;
      const kind = field === fields.turn ? 'turn' : field === fields.move ? 'move' : 'goto';
      element(root, `mission-${kind}`, HTMLButtonElement).click();
    });
    element(root, 'mission-stop', HTMLButtonElement).addEventListener('click', () => {
      this.watch.cancel();
      const sent = stop();
      this.say(sent ? 'sent stop' : 'not sent: no connection', !sent);
    });
    element(root, 'mission-clear-waypoints', HTMLButtonElement).addEventListener('click', () => {
      this.gotoField.value = '';
      this.showDraft();
    });
    this.gotoField.addEventListener('input', () => this.showDraft());
  }

  /**
   * @param {string} text
   * @param {boolean} bad
   */
  say(text, bad) {
    this.result.textContent = text;
    this.result.classList.toggle('bad', bad);
  }

  // The waypoints typed so far, for the map (what parses; nothing while the text is wrong).
  showDraft() {
    const { waypoints } = parseWaypoints(this.gotoField.value);
    this.onDraft(waypoints ?? []);
  }

  // A click on the map: one more waypoint at the end of the list.
  /** @param {Point} p */
  addWaypoint(p) {
    const { waypoints } = parseWaypoints(this.gotoField.value);
    const list = this.gotoField.value.trim() === '' ? [] : waypoints;
    if (!list) {
      this.say('the waypoints typed are not x,y; x,y: fix or clear them before clicking the map', true);
      return;
    }
    this.gotoField.value = formatWaypoints([...list, p]);
    this.showDraft();
  }

  /**
   * @param {MissionStatus | undefined} mission
   * @param {{ sent?: VelocityCommand | null, pose?: Pose }} [velocity]  missionSummary's
   */
  update(mission, velocity) {
    this.mission = mission;
    this.summary.textContent = missionSummary(mission, velocity);
    this.summary.dataset.state = mission?.state ?? 'none';
    this.progress.value = mission && finite(mission.progress) ? Math.min(1, Math.max(0, mission.progress)) : 0;
    this.reason.textContent = mission?.reason ? `reason: ${mission.reason}` : '';
  }

  // Whether a mission runs now (or was just sent): the sender keeps it alive.
  active() {
    return this.watch.active(this.mission, performance.now());
  }

  /** @param {boolean} enabled */
  setEnabled(enabled) {
    for (const kind of ['turn', 'move', 'goto']) {
      const button = element(this.form, `mission-${kind}`, HTMLButtonElement);
      button.disabled = !enabled;
      button.title = enabled ? '' : 'take control to send a mission';
    }
  }
}
