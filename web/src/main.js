// The console: connects to the link server, shows its status, and while it holds control sends
// the operator's gamepad (or keyboard) reading at 20 Hz, continuously — the driver stops the
// rover after 0.5 s without input (docs/operator-protocol.md, "Control"). While a mission runs
// and the reading is neutral it sends a heartbeat at 20 Hz instead (mission.js); in velocity mode
// it sends `velocity` instead of the reading (velocity.js).

import './style.css';
import { Link, websocketUrl, exchangeToken, addressWithoutToken } from './link.js';
import { pollGamepad, mergeReadings, gamepadMessage, neutralReading, applyDeadZone } from './gamepad.js';
import { Keyboard } from './keyboard.js';
import { StatusPanel } from './status.js';
import { Plots } from './plots.js';
import { RoverView } from './view3d.js';
import { ConfigPanel } from './config.js';
import { MapPanel, pathLength } from './map.js';
import { MissionPanel, inputToSend } from './mission.js';
import { VelocityPanel, velocityText } from './velocity.js';
import { element } from './dom.js';

/** @typedef {import('./protocol').GamepadReading} GamepadReading */
/** @typedef {import('./link.js').LinkState} LinkState */

const SEND_PERIOD_MS = 50;  // 20 Hz, ten messages within the driver's 0.5 s timeout
const BUTTON_NAMES = ['A', 'B', 'X', 'Y', 'LB', 'RB', 'LT', 'RT', 'back', 'start', 'LS', 'RS',
  'up', 'down', 'left', 'right', 'home'];

/** @param {string} id */
const $ = (id) => element(document, id, HTMLElement);
/** @param {string} id */
const button = (id) => element(document, id, HTMLButtonElement);

const token = new URLSearchParams(location.search).get('token');
const link = new Link(websocketUrl(location));
const statusPanel = new StatusPanel(document);
const plots = new Plots($('plot-area'));
const view = new RoverView($('view3d'));
const config = new ConfigPanel(element(document, 'config-form', HTMLFormElement), {
  send: (message) => link.send(message),
  clearFaults: () => link.send({ type: 'clear_faults' }),
});
const keyboard = new Keyboard(window, { onStop: stop });
const map = new MapPanel(element(document, 'map-canvas', HTMLCanvasElement), {
  onClick: (p) => mission.addWaypoint(p),
});
const mission = new MissionPanel(document, {
  send: (message) => link.sendInput(message),
  stop,
  onDraft: (points) => map.setDraft(points),
});
const velocity = new VelocityPanel(document, { send: (message) => link.sendInput(message) });
$('map-clear').addEventListener('click', () => map.clearTrack());

// For the browser's developer tools and the tests: the link, the views and the newest status.
window.marsokhod = { link, view, map, status: null };

// STOP latches: the console sends the neutral reading until the operator has let go of every
// stick, button and key — otherwise its next 20 Hz message, the stick still pushed, would drive
// on at once (a `stop` lasts only until the controller's next input).
let stopLatched = false;

/** @param {GamepadReading} reading */
function isNeutral(reading) {
  return reading.axes.every((v) => applyDeadZone(v) === 0) && !reading.buttons.some(Boolean);
}

function stop() {
  stopLatched = true;
  velocity.cancel();
  const sent = link.stop();
  if (!sent) showError('STOP not sent: not connected (a controlling console that drops off stops the rover anyway)');
  return sent;
}

// The driver holds a stop until the controller's input is neutral (docs/operator-protocol.md):
// the banner says who stopped and why until the status says the rover is re-armed.
/** @param {string} reason */
function showStopBanner(reason) {
  const banner = $('stop-banner');
  banner.textContent = `STOPPED: ${reason}. The rover stays stopped until the controlling ` +
    'console centres its sticks (no gait speed, no joint button).';
  banner.hidden = false;
}

/** @param {string} text */
function showError(text) {
  const box = $('link-error');
  box.textContent = `${new Date().toLocaleTimeString()}  ${text}`;
  box.hidden = false;
}

function showLinkState() {
  /** @type {Record<LinkState, string>} */
  const labels = {
    connecting: 'connecting…',
    'read-only': 'connected, read-only',
    'in-control': 'in control',
    disconnected: 'disconnected',
  };
  let text = labels[link.state];
  if (link.state === 'read-only' || link.state === 'in-control') {
    const who = link.controller == null ? 'nobody controls'
      : link.controller === link.clientId ? `client ${link.clientId}` : `client ${link.controller} controls`;
    text += ` · ${who}`;
  }
  const element = $('link-state');
  element.textContent = text;
  element.dataset.state = link.state;
  const connected = link.state === 'read-only' || link.state === 'in-control';
  button('take-control').disabled = !connected || link.inControl;
  button('release-control').disabled = !link.inControl;
  config.setEnabled(link.inControl);
  mission.setEnabled(link.inControl);
  velocity.setEnabled(link.inControl);
}

link.on('state', showLinkState);
link.on('hello', ({ calibration: c, velocityLimits }) => {
  velocity.setLimits(velocityLimits);
  view.clearSoil();  // a reconnect may find the rover on rigid ground: no ruts from before
  $('calibration').textContent = c && c.file
    ? `calibration: ${c.file} (${c.procedures.join(', ') || 'no procedures'})`
    : 'calibration: none (nominal configuration)';
});
link.on('control', showLinkState);
link.on('stopped', ({ reason }) => {
  velocity.cancel();
  showStopBanner(reason);
});
link.on('error', ({ text }) => showError(text));
link.on('pong', ({ rtt_ms }) => { $('link-state').title = `round trip ${rtt_ms.toFixed(0)} ms`; });
link.on('status', ({ status }) => {
  window.marsokhod.status = status;
  statusPanel.update(status);
  config.showSettings(status.settings);
  if (status.stop_latched) showStopBanner(status.stop_reason);
  else $('stop-banner').hidden = true;
  plots.add(status);
  view.update(status);
  $('view-source').textContent = status.truth ? '(simulator ground truth)' : '(joint angles, rover placed level)';
  map.update(status);
  mission.update(status.mission, { sent: velocity.active ? velocity.sent : null, pose: status.pose });
  $('legend-truth').hidden = !status.truth?.odometry;
  const info = `track ${pathLength(map.tracks.estimated).toFixed(2)} m` +
    (map.tracks.truth.length > 1 ? `, true ${pathLength(map.tracks.truth).toFixed(2)} m` : '');
  if ($('map-info').textContent !== info) $('map-info').textContent = info;
});

$('take-control').addEventListener('click', () => link.takeControl());
$('release-control').addEventListener('click', () => link.releaseControl());
$('stop').addEventListener('click', stop);

// The operator's reading: the first standard-mapping gamepad, with the keyboard on top.
/** @type {string | null} */
let padPresent = null;
function currentReading() {
  const polled = pollGamepad();
  const padId = polled ? polled.pad.id : null;
  if (padId !== padPresent) {
    padPresent = padId;
    $('input-source').textContent = padId ? `gamepad: ${padId}` : 'no gamepad: keyboard';
  }
  return mergeReadings(polled?.reading ?? null, keyboard.reading());
}

/** @param {GamepadReading} reading */
function showReading(reading) {
  /**
   * @param {HTMLElement} dot
   * @param {number} x
   * @param {number} y
   */
  const place = (dot, x, y) => {
    dot.style.left = `${50 + 45 * x}%`;
    dot.style.top = `${50 + 45 * y}%`;
  };
  place($('stick-left'), reading.axes[0], reading.axes[1]);
  place($('stick-right'), reading.axes[2], reading.axes[3]);
  const pressed = BUTTON_NAMES.filter((_, i) => reading.buttons[i]);
  $('buttons-pressed').textContent = `buttons: ${pressed.length ? pressed.join(' ') : 'none'}`;
}

/** @param {number} now */
function frame(now) {
  showReading(currentReading());
  plots.draw(now);
  view.draw();
  map.draw();
  requestAnimationFrame(frame);
}

// Sent from a timer, not from animation frames: browsers pause those in a hidden tab.
let tick = 0;
setInterval(() => {
  let sending = 'nothing (read-only)';
  tick += 1;
  if (link.inControl && document.visibilityState === 'visible') {
    const reading = currentReading();
    const neutral = isNeutral(reading);
    if (stopLatched && neutral) stopLatched = false;
    if (velocity.active && !stopLatched) {
      const { message, source } = velocity.next(reading, mission.active());
      link.sendInput(message);
      sending = message.type === 'heartbeat'
        ? 'heartbeat at 20 Hz: the mission drives (push the left stick to take over)'
        : `velocity ${velocityText(message)} at 20 Hz (${source === 'form' ? 'the form\'s, until stop'
          : source === 'stick' ? 'left stick' : 'neutral: the rover stops'}; right stick and buttons off)`;
    } else {
      const what = inputToSend({ missionActive: mission.active(), neutral, stopLatched, tick });
      if (what === 'gamepad') link.sendInput(gamepadMessage(stopLatched ? neutralReading() : reading));
      else if (what === 'heartbeat') link.sendInput({ type: 'heartbeat' });
      sending = stopLatched ? 'neutral: STOPPED, let go of every stick and key to drive again'
        : what === 'gamepad' ? 'the reading at 20 Hz'
          : 'heartbeat at 20 Hz: the mission drives (push a stick to take over)';
    }
  } else if (link.inControl) {
    sending = 'nothing: page hidden, the rover stops';
  }
  if ($('send-state').textContent !== sending) $('send-state').textContent = sending;
  document.body.classList.toggle('stopped', stopLatched);
}, SEND_PERIOD_MS);

// A hidden page cannot see its operator: stop now rather than after the driver's timeout.
document.addEventListener('visibilitychange', () => {
  if (document.visibilityState === 'hidden' && link.inControl) link.stop();
});

// The token goes once, for the session cookie, and leaves the address bar; without one in the
// address a cookie from before (a reload) may still open the WebSocket.
async function start() {
  showLinkState();
  if (token) {
    history.replaceState(null, '', addressWithoutToken(location.href));
    const refused = await exchangeToken(location, token);
    if (refused) {
      link.setState('disconnected');
      showError(refused);
      return;
    }
  }
  if (!token) {
    link.on('error', () => {
      if (!link.everOpened) {
        showError('no token in the page address and no session: open the address the server ' +
          'printed, http://HOST:PORT/?token=…');
      }
    });
  }
  link.connect();
}
start();
requestAnimationFrame(frame);
