// The console in a real browser (Debian's chromium, headless, via playwright-core) against the
// real server: `marsokhod run` — the simulator, the driver and the link server in one process,
// in real time. Every wait is bounded and waits for a condition, never for a fixed time.
//   npm test            (in web/; builds dist/ first)
//   MARSOKHOD_BIN=…  CHROMIUM_PATH=…   to use other binaries

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import http from 'node:http';
import {
  checkPrerequisites, startServer, launchBrowser, openConsole, setPad, latestStatus,
  takeControl, waitForStatus, waitForLinkState, screenshot, WHEELS,
} from './harness.mjs';

const TOKEN = 'console-test-token-0123456789';
const STICK_UP = [0, -1, 0, 0];
const CENTERED = [0, 0, 0, 0];
const DRIVEN_M = 0.05;  // a displacement no noise or settling makes: the rover drove
const STARTUP_TIMEOUT_MS = 20000;
const MOVE_TIMEOUT_MS = 8000;
// The server's driver stops the rover after 0.5 s without input; a stop reaches it at once.
const STOP_TIMEOUT_MS = 1500;
// The driver's control cycle h (config/marsokhod.toml [cycle] period_s) and the server's status
// period (docs/operator-protocol.md), in seconds.
const CYCLE_S = 0.0156;
const STATUS_PERIOD_S = 0.05;
const STILL_DUTY = 0.02;
const close = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual} is not ${expected} ± ${tolerance}`);

let server;
let browser;
const pages = [];

const wheelsDriveForward = (s) => ['FL', 'FR', 'CL', 'CR', 'BL', 'BR'].every((w) => s.motors[w].duty > 0.1);
const wheelsStill = (s, limit) => ['FL', 'FR', 'CL', 'CR', 'BL', 'BR'].every((w) => Math.abs(s.motors[w].duty) < limit);

async function open(options) {
  const page = await openConsole(browser, server.url, options);
  pages.push(page);
  return page;
}

// Drives forward with the scripted pad until the rover has moved and every wheel has duty.
async function driveForward(page) {
  const from = (await latestStatus(page)).truth.position_m;
  await setPad(page, { axes: STICK_UP });
  await waitForStatus(page, 'the rover drove forward', (s, a) =>
    Math.hypot(s.truth.position_m[0] - a[0], s.truth.position_m[1] - a[1]) > a[2] &&
    ['FL', 'FR', 'CL', 'CR', 'BL', 'BR'].every((w) => s.motors[w].duty > 0.1),
  [from[0], from[1], DRIVEN_M], MOVE_TIMEOUT_MS);
}

before(async () => {
  checkPrerequisites();
  server = await startServer(TOKEN);
  browser = await launchBrowser();
});

after(async () => {
  for (const page of pages) await page.context().close().catch(() => {});
  await browser?.close();
  if (server) await server.stop();
});

test('the page loads and shows live status', async () => {
  const page = await open();
  await waitForLinkState(page, 'read-only', 5000);
  await waitForStatus(page, 'the driver finished its startup', (s) => s.mode === 'driving', null, STARTUP_TIMEOUT_MS);
  const first = await latestStatus(page);
  const shownFirst = await page.textContent('#st-mission');
  await waitForStatus(page, 'mission time advanced by 0.3 s', (s, t) => s.mission_time_s > t + 0.3,
    first.mission_time_s, 3000);
  assert.notEqual(await page.textContent('#st-mission'), shownFirst, 'the shown mission time changes');
  assert.match(await page.textContent('#st-voltage'), /^\d+\.\d \(\d+\.\d\) V$/);
  const header = await page.$$eval('#motor-table thead th', (ths) => ths.map((th) => th.textContent));
  assert.deepEqual(header.slice(1), ['FL', 'FR', 'CL', 'CR', 'BL', 'BR', 'AF', 'AR']);
  const rows = await page.$$eval('#motor-table tbody th', (ths) => ths.map((th) => th.textContent));
  assert.deepEqual(rows, ['pos', 'vel', 'load', 'τ', 'duty', 'cmd', 'hold']);
  assert.match(await page.textContent('#motor-table tbody tr:nth-child(1) td:nth-child(8)'), /^-?\d+\.\d{3}$/,
    'AF position shown');
  assert.ok(first.truth, 'marsokhod run attaches the simulator truth');
  assert.equal(await page.textContent('#view-source'), '(simulator ground truth)');
  assert.equal(await page.locator('#view3d canvas').count(), 1, 'the 3-D view has its canvas');
  assert.equal(await page.locator('#plot-area .uplot').count(), 5, 'five charts');
  assert.equal(await page.isDisabled('#config-apply'), true, 'configuration needs control');
  await screenshot(page, 'console-read-only.png');
  assert.deepEqual(page.problems, []);
});

test('a scripted gamepad drives the rover forward', async () => {
  const page = await open({ gamepad: true });
  await waitForLinkState(page, 'read-only', 5000);
  assert.match(await page.textContent('#input-source'), /scripted test pad/);
  await takeControl(page);
  await driveForward(page);
  const status = await latestStatus(page);
  assert.ok(status.targets.v1_radps > 2, `full deflection asks for full speed, got ${status.targets.v1_radps}`);
  assert.equal(status.targets.v2_radps, 0);
  await screenshot(page, 'console-driving-gamepad.png');
  await setPad(page, { axes: CENTERED });
  await waitForStatus(page, 'the wheels stopped after the stick was centered', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  assert.deepEqual(page.problems, []);
});

// The map's tracks as the page holds them: their lengths [m] and point counts, and how many
// pixels of the canvas have each track's colour.
function mapState(page) {
  return page.evaluate(() => {
    const { map } = window.marsokhod;
    const length = (points) => points.reduce((sum, p, i) =>
      (i === 0 ? 0 : sum + Math.hypot(p.x - points[i - 1].x, p.y - points[i - 1].y)), 0);
    const canvas = document.getElementById('map-canvas');
    const ctx = canvas.getContext('2d');
    const data = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
    const count = (r, g, b) => {
      let n = 0;
      for (let i = 0; i < data.length; i += 4) {
        if (Math.abs(data[i] - r) < 8 && Math.abs(data[i + 1] - g) < 8 && Math.abs(data[i + 2] - b) < 8 && data[i + 3] > 200) n += 1;
      }
      return n;
    };
    const last = (points) => points[points.length - 1] ?? null;
    return {
      estimatedM: length(map.tracks.estimated), estimatedPoints: map.tracks.estimated.length,
      truthM: length(map.tracks.truth), truthPoints: map.tracks.truth.length,
      estimatedEnd: last(map.tracks.estimated), truthEnd: last(map.tracks.truth),
      bluePixels: count(0x1f, 0x6f, 0xeb), orangePixels: count(0xe8, 0x59, 0x0c),
      info: document.getElementById('map-info').textContent,
      truthLegend: !document.getElementById('legend-truth').hidden,
    };
  });
}

// Records the type of every message the page sends from now on (sentTypes reads them).
function spyOnSends(page) {
  return page.evaluate(() => {
    const { link } = window.marsokhod;
    window.__sent = [];
    if (!window.__spying) {
      const send = link.send.bind(link);
      link.send = (message) => { window.__sent.push(message.type); return send(message); };
      window.__spying = true;
    }
  });
}

function sentTypes(page) {
  return page.evaluate(() => window.__sent);
}

// Waits until `predicate(mapState)` holds, polled every 50 ms from here.
async function waitForMap(page, what, predicate, timeoutMs) {
  const deadline = Date.now() + timeoutMs;
  let state;
  for (;;) {
    state = await mapState(page);
    if (predicate(state)) return state;
    if (Date.now() >= deadline) break;
    await new Promise((resolve) => setTimeout(resolve, 50));
  }
  throw new Error(`timed out after ${timeoutMs} ms waiting until ${what}; the map: ${JSON.stringify(state)}`);
}

test('the map draws the estimated track growing while driving, and the true track beside it', async () => {
  const page = pages[1];  // holds control, the pad centred
  await waitForStatus(page, 'the rover stands still', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  await page.click('#map-clear');
  const cleared = await mapState(page);
  assert.ok(cleared.estimatedM < 0.02, `a cleared track is (nearly) empty: ${cleared.estimatedM} m`);
  const status = await latestStatus(page);
  assert.ok(status.truth.odometry, 'marsokhod run sends the truth in the odometry frame');
  for (const key of ['x_m', 'y_m', 'heading_rad']) assert.equal(typeof status.truth.odometry[key], 'number', key);
  assert.equal(typeof status.pose.x_m, 'number');

  await setPad(page, { axes: STICK_UP });
  const grown = await waitForMap(page, 'the estimated track grew by 0.15 m', (m) => m.estimatedM > 0.15, MOVE_TIMEOUT_MS);
  const more = await waitForMap(page, 'the estimated track grew further', (m) => m.estimatedM > grown.estimatedM + 0.05, MOVE_TIMEOUT_MS);
  await setPad(page, { axes: CENTERED });
  await waitForStatus(page, 'the wheels stopped after the stick was centered', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  assert.ok(more.estimatedPoints > grown.estimatedPoints, 'points are added as the rover drives');
  assert.ok(more.truthM > 0.1, `the true track grew too: ${more.truthM} m`);
  assert.equal(more.truthLegend, true, 'the legend names the true track');
  // Both tracks run the same way: their ends lie close together against the way driven.
  const apart = Math.hypot(more.estimatedEnd.x - more.truthEnd.x, more.estimatedEnd.y - more.truthEnd.y);
  assert.ok(apart < 0.5 * more.estimatedM, `estimate and truth ${apart} m apart after ${more.estimatedM} m`);
  assert.ok(more.estimatedEnd.x > 0.1, `forward is +x: ${JSON.stringify(more.estimatedEnd)}`);
  assert.ok(more.bluePixels > 50 && more.orangePixels > 20,
    `both tracks drawn: ${more.bluePixels} blue, ${more.orangePixels} orange pixels`);
  assert.match(more.info, /^track \d+\.\d\d m, true \d+\.\d\d m$/);
  await screenshot(page, 'console-map.png');
  assert.deepEqual(page.problems, []);
});

test('the mission form refuses bad input before sending, and a click on the map adds a waypoint', async () => {
  const page = pages[1];  // in control
  const result = () => page.textContent('#mission-result');
  await spyOnSends(page);
  await page.fill('#mission-form input[name=turn_deg]', 'left');
  await page.click('#mission-turn');
  assert.equal(await result(), 'turn: "left" is not a number (°)');
  await page.fill('#mission-form input[name=move_m]', '');
  await page.click('#mission-move');
  assert.equal(await result(), 'move: empty; type a number in m');
  await page.fill('#mission-form input[name=move_m]', '250');
  await page.click('#mission-move');
  assert.equal(await result(), 'move: 250 is out of range; allowed −100..100 m');
  await page.fill('#mission-form input[name=goto]', '1,2; 3');
  await page.click('#mission-goto');
  assert.equal(await result(), 'go to: waypoint 2: "3" is not x,y (two numbers in metres)');
  await page.fill('#mission-form input[name=move_m]', '1');
  await page.fill('#mission-form input[name=settle_s]', '0');
  await page.click('#mission-move');
  assert.equal(await result(), 'stand: 0 s is out of range; allowed 0 < s ≤ 60 s (blank: the configured one)');
  await page.fill('#mission-form input[name=settle_s]', '');
  await page.fill('#mission-form input[name=move_m]', '');
  assert.equal(await page.getAttribute('#mission-result', 'class'), 'hint bad');
  const types = await sentTypes(page);
  assert.ok(types.includes('gamepad'), 'the 20 Hz reading goes on');
  assert.equal(types.includes('mission'), false, `nothing refused was sent: ${[...new Set(types)]}`);

  // A space in the waypoints' field types a space, it is not STOP there.
  await page.fill('#mission-form input[name=goto]', '');
  await page.click('#mission-form input[name=goto]');
  await page.keyboard.type('1,0; 2,0');
  assert.equal(await page.inputValue('#mission-form input[name=goto]'), '1,0; 2,0');
  assert.doesNotMatch(await page.textContent('#send-state'), /STOPPED/);
  await page.click('#mission-clear-waypoints');
  assert.equal(await page.inputValue('#mission-form input[name=goto]'), '');

  // Clicks on the map: waypoints where the map shows them, in metres.
  // The view refits with every status: the first click and the transform it meets are read in
  // one task of the page; the second is a real click.
  const box = await page.locator('#map-canvas').boundingBox();
  const expected = await page.evaluate(([x, y]) => {
    const canvas = document.getElementById('map-canvas');
    const rect = canvas.getBoundingClientRect();
    const t = window.marsokhod.map.transform;
    // A mouse event's clientX, clientY are whole pixels.
    const clientX = Math.round(rect.left + x);
    const clientY = Math.round(rect.top + y);
    canvas.dispatchEvent(new MouseEvent('click', { clientX, clientY, bubbles: true }));
    return { x: (clientX - rect.left - t.ox) / t.scale, y: (t.oy - (clientY - rect.top)) / t.scale };
  }, [box.width / 4, box.height / 2]);
  await page.click('#map-canvas', { position: { x: box.width / 2, y: box.height / 4 } });
  const typed = await page.inputValue('#mission-form input[name=goto]');
  const points = typed.split(';').map((p) => p.split(',').map(Number));
  assert.equal(points.length, 2, `two waypoints: "${typed}"`);
  close(points[0][0], expected.x, 0.005 + 1e-9, 'first waypoint x (to the centimetre)');
  close(points[0][1], expected.y, 0.005 + 1e-9, 'first waypoint y');
  const draft = await page.evaluate(() => window.marsokhod.map.draft.length);
  assert.equal(draft, 2, 'the map shows the typed waypoints');
  await page.click('#mission-clear-waypoints');
  assert.deepEqual(page.problems, []);
});

test('a move of 0.3 m from the form runs, is reached, and draws a track of 0.3 m', async (t) => {
  const page = pages[1];  // in control, the pad centred
  await waitForStatus(page, 'the rover stands still', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  const start = await latestStatus(page);
  assert.ok(start.mission, 'the server reports missions (status.mission)');
  await page.click('#map-clear');
  await spyOnSends(page);
  await page.fill('#mission-form input[name=move_m]', '0.3');
  await page.fill('#mission-form input[name=settle_s]', '2');  // its own standing: 2 s a leg
  await page.click('#mission-move');
  await page.fill('#mission-form input[name=settle_s]', '');
  assert.equal(await page.textContent('#mission-result'),
    'sent mission {"kind":"move","distance_m":0.3,"settle_s":2}');
  // Every state the statuses show, in order, until the mission is reached.
  const id = start.mission.id + 1;
  const states = [];
  await waitForStatus(page, `mission ${id} was reached`, (s) => {
    const m = s.mission;
    if (m && m.id === id && states[states.length - 1] !== m.state) states.push(m.state);
    return m?.id === id && m.state !== 'running' && states.includes('running');
  }, null, 30000).catch(async (err) => {
    throw new Error(`${err.message}; states seen ${JSON.stringify(states)}, sent ${[...new Set(await sentTypes(page))]}`);
  });
  const end = await latestStatus(page);
  assert.equal(end.mission.state, 'reached', `states ${JSON.stringify(states)}, reason "${end.mission.reason}"`);
  assert.deepEqual(states, ['running', 'reached']);
  assert.equal(end.mission.kind, 'move');
  assert.equal(end.mission.settle_s, 2, 'the driver stood the mission\'s own 2 s');
  const types = await sentTypes(page);
  assert.ok(types.includes('mission') && types.includes('heartbeat'),
    `the console sent the mission and kept it alive: ${[...new Set(types)]}`);
  await waitForStatus(page, 'the rover stopped at the end of the move', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  const stopped = await latestStatus(page);
  close(stopped.pose.distance_m - start.pose.distance_m, 0.3, 0.05, 'the estimated distance driven');
  const map = await mapState(page);
  close(map.estimatedM, 0.3, 0.05, 'the estimated track on the map');
  assert.ok(map.truthM > 0.2, `the true track beside it: ${map.truthM} m`);
  assert.match(await page.textContent('#mission-summary'), new RegExp(`^#${id} move · reached`));
  const progress = await page.evaluate(() => document.getElementById('mission-progress').value);
  assert.ok(progress > 0.9, `the progress bar full: ${progress}`);
  assert.match(await page.textContent('#send-state'), /the reading at 20 Hz/, 'back to the reading once reached');
  t.diagnostic(`states ${states.join(' → ')}; estimated distance ${(stopped.pose.distance_m - start.pose.distance_m).toFixed(3)} m, ` +
    `track ${map.estimatedM.toFixed(3)} m, true track ${map.truthM.toFixed(3)} m`);
  await screenshot(page, 'console-mission-move.png');
  assert.deepEqual(page.problems, []);
});

// Velocity mode against the simulator. The wheels reach v/r = 0.8 rad/s through the ramp (4.14)
// at μ = 2 rad/s² in 0.4 s, during which the rover covers at most 0.4 s · 0.1 m/s / 2 = 0.02 m
// less than at full speed; straight on hard ground the wheels hardly slip. So the speed is
// measured over ≥ 2.5 s of simulated time (mission_time_s, not the wall clock: a loaded machine
// runs the simulator late, not fast) starting 0.5 s after the driver took the velocity, and must
// be 0.1 m/s within 10 % — the true track's and the dead reckoning's alike.
const VELOCITY_MPS = 0.1;
const RAMP_S = 0.5;
const MEASURE_S = 2.5;
// Ramping down takes 0.4 s; the wait's bound only has to outlast a loaded machine.
const REST_TIMEOUT_MS = 5000;
const planar = (s) => Math.hypot(s.truth.velocity_mps[0], s.truth.velocity_mps[1]);

test('velocity mode: 0.1 m/s from the form drives the rover at 0.1 m/s, the stick at the limit, stop and off bring it to rest', async (t) => {
  const page = pages[1];  // in control, the pad centred
  const toggle = '#velocity-form input[name=velocity_mode]';
  await waitForStatus(page, 'the rover stands still', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  assert.equal(await page.isChecked(toggle), false, 'velocity mode is off by default');
  assert.equal(await page.isDisabled('#velocity-send'), true, 'the form needs the mode on');
  assert.equal(await page.textContent('#velocity-limits'), 'limits ±0.281 m/s, ±0.536 rad/s', 'the hello\'s limits');
  await page.check(toggle);
  // Neutral in velocity mode: zero velocity, which the driver runs as a velocity mission.
  await waitForStatus(page, 'zero velocity started a velocity mission',
    (s) => s.mission.kind === 'velocity' && s.mission.state === 'running' && s.targets.v1_radps === 0, null, 3000);
  await spyOnSends(page);  // from here on, in velocity mode
  assert.match(await page.textContent('#send-state'), /^velocity v 0\.000 m\/s, ω 0\.000 rad\/s at 20 Hz \(neutral/);

  await page.fill('#velocity-form input[name=v_mps]', '0.5');
  await page.click('#velocity-send');
  assert.equal(await page.textContent('#velocity-result'), 'v: 0.5 is out of range; allowed −0.281..0.281 m/s');
  await page.fill('#velocity-form input[name=v_mps]', String(VELOCITY_MPS));
  await page.fill('#velocity-form input[name=yaw_radps]', '0');
  await page.click('#velocity-send');
  assert.equal(await page.textContent('#velocity-result'), 'sending v 0.100 m/s, ω 0.000 rad/s until stop');
  const r = 0.125;  // the wheel radius: v1 = v/r
  await waitForStatus(page, 'the driver took 0.1 m/s as v1 = 0.8 rad/s', (s, v1) => Math.abs(s.targets.v1_radps - v1) < 1e-9,
    VELOCITY_MPS / r, 3000);
  const taken = (await latestStatus(page)).mission_time_s;
  await waitForStatus(page, 'the wheels came up to speed', (s, t0) => s.mission_time_s >= t0, taken + RAMP_S, 5000);
  const a = await latestStatus(page);
  await waitForStatus(page, `${MEASURE_S} s of driving went by`, (s, t0) => s.mission_time_s >= t0, a.mission_time_s + MEASURE_S, 15000);
  const b = await latestStatus(page);
  const dt = b.mission_time_s - a.mission_time_s;
  const trueSpeed = Math.hypot(b.truth.position_m[0] - a.truth.position_m[0], b.truth.position_m[1] - a.truth.position_m[1]) / dt;
  const estimatedSpeed = (b.pose.distance_m - a.pose.distance_m) / dt;
  t.diagnostic(`over ${dt.toFixed(2)} s simulated: true ${trueSpeed.toFixed(4)} m/s, estimated ${estimatedSpeed.toFixed(4)} m/s`);
  close(trueSpeed, VELOCITY_MPS, 0.1 * VELOCITY_MPS, 'the true speed');
  close(estimatedSpeed, VELOCITY_MPS, 0.1 * VELOCITY_MPS, 'the dead reckoning\'s speed');
  assert.ok(b.truth.position_m[0] - a.truth.position_m[0] > 0.8 * VELOCITY_MPS * dt, 'forward, not sideways');
  assert.equal(b.mission.kind, 'velocity');
  assert.equal(b.mission.state, 'running');
  assert.equal(b.mission.id, a.mission.id, 'one velocity mission all along (the form re-sends, no timeout)');
  assert.equal(b.operator_timeout, false);
  assert.match(await page.textContent('#mission-summary'),
    new RegExp(`^#${b.mission.id} velocity · running · sent v 0\\.100 m/s, ω 0\\.000 rad/s · estimated 0\\.\\d{3} m/s`));
  assert.match(await page.textContent('#send-state'), /^velocity v 0\.100 m\/s, ω 0\.000 rad\/s at 20 Hz \(the form's, until stop/);
  const types = new Set(await sentTypes(page));
  assert.ok(types.has('velocity') && !types.has('gamepad'), `velocity instead of the reading: ${[...types]}`);
  await screenshot(page, 'console-velocity-form.png');

  await page.click('#velocity-stop');
  assert.equal(await page.textContent('#velocity-result'), 'sent zero velocity');
  await waitForStatus(page, 'the rover came to rest after stop', (s) => wheelsStill(s, STILL_DUTY) && planar(s) < 0.01,
    null, REST_TIMEOUT_MS);
  assert.equal((await latestStatus(page)).mission.kind, 'velocity', 'zero velocity goes on while the mode is on');

  // The stick: full up is the largest speed, r·v1ᵈ, i.e. v1 = v1ᵈ = 2.25 rad/s.
  await setPad(page, { axes: STICK_UP });
  await waitForStatus(page, 'the stick asks for the largest speed', (s) => Math.abs(s.targets.v1_radps - 2.25) < 1e-9, null, 3000);
  await setPad(page, { axes: CENTERED });
  await waitForStatus(page, 'the rover came to rest with the stick centred', (s) => wheelsStill(s, STILL_DUTY) && planar(s) < 0.01,
    null, REST_TIMEOUT_MS);

  // The form's velocity again, then the mode off: the gamepad reading again, the mission ends.
  await page.click('#velocity-send');
  await waitForStatus(page, 'the form\'s velocity again', (s, v1) => Math.abs(s.targets.v1_radps - v1) < 1e-9, VELOCITY_MPS / r, 3000);
  await page.uncheck(toggle);
  await waitForStatus(page, 'the velocity mission ended with the mode off',
    (s) => s.mission.kind === 'velocity' && s.mission.state === 'aborted', null, 3000);
  await waitForStatus(page, 'the rover came to rest with the mode off', (s) => wheelsStill(s, STILL_DUTY) && planar(s) < 0.01,
    null, REST_TIMEOUT_MS);
  assert.match(await page.textContent('#send-state'), /the reading at 20 Hz/);
  assert.equal(await page.isDisabled('#velocity-send'), true);
  assert.deepEqual(page.problems, []);
});

test('the keyboard drives the rover (W), and the configuration reaches the server', async () => {
  const page = pages[1];  // the gamepad's page holds control; its pad is centered
  const form = page.locator('#config-form');
  await form.locator('input[name=speed_scale]').fill('1');
  await form.locator('select[name=slant_response]').selectOption('on');
  await page.click('#config-apply');
  assert.match(await page.textContent('#config-result'),
    /^sent \{"behaviours":\{"slant_response":true\},"speed_scale":1\}$/);

  const from = (await latestStatus(page)).truth.position_m;
  await page.locator('body').click({ position: { x: 5, y: 300 } });  // the keyboard's focus on the page
  await page.keyboard.down('KeyW');
  await waitForStatus(page, 'W drove the rover forward', (s, a) =>
    s.targets.v1_radps > 2 && Math.hypot(s.truth.position_m[0] - a[0], s.truth.position_m[1] - a[1]) > a[2],
  [from[0], from[1], DRIVEN_M], MOVE_TIMEOUT_MS);
  await screenshot(page, 'console-driving-keyboard.png');
  await page.keyboard.up('KeyW');
  await waitForStatus(page, 'the wheels stopped after W was released', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  const error = await page.textContent('#link-error');
  assert.doesNotMatch(error, /speed_scale|slant_response|behaviours/, 'the server took the configuration');
  assert.deepEqual(page.problems, []);
});


test('the configuration panel shows the settings in force, and follows a change', async () => {
  const page = pages[1];  // holds control
  const form = page.locator('#config-form');
  const shown = (name) => form.locator(`[name=${name}]`).evaluate((f) =>
    (f instanceof HTMLInputElement ? f.placeholder : f.options[0].text));
  const before = (await latestStatus(page)).settings;
  assert.ok(before, 'the status reports the settings in force');
  assert.equal(before.behaviours.slant_response, true, 'the previous test switched it on');
  assert.equal(await shown('slant_response'), 'on (in force)');
  assert.equal(await shown('max_drop_v'), `${before.max_drop_v} (in force)`);
  assert.equal(await shown('speed_scale'), `${before.speed_scale} (in force)`);
  assert.equal(await shown('load_distribution'),
    `${{ off: 'off', v: 'hᵛ (6.5)', s: 'hˢ (6.6)' }[before.load_distribution]} (in force)`);

  // Υ changed from the form: the driver takes it, the status says so, the field shows it.
  const changed = before.max_drop_v === 2.5 ? 3 : 2.5;
  await form.locator('input[name=max_drop_v]').fill(String(changed));
  await page.click('#config-apply');
  await waitForStatus(page, `the driver took Υ = ${changed} V`, (s, v) => s.settings.max_drop_v === v, changed, 3000);
  await page.waitForFunction((v) => document.querySelector('#config-form [name=max_drop_v]').placeholder === `${v} (in force)`,
    changed, { timeout: 3000 });
  await form.locator('input[name=max_drop_v]').fill(String(before.max_drop_v));
  await page.click('#config-apply');
  await waitForStatus(page, 'Υ is back', (s, v) => s.settings.max_drop_v === v, before.max_drop_v, 3000);
  assert.deepEqual(page.problems, []);
});
test('STOP (button or space bar) stops the rover while the stick is still pushed', async () => {
  const page = pages[1];
  for (const how of ['button', 'space']) {
    // Centred, and seen centred: the console samples the pad at 20 Hz, and after the first STOP
    // only a sample of the centred stick re-arms it. Pushing the stick again before one was taken
    // (a busy machine delays the timer) would leave it latched and sending neutral.
    await setPad(page, { axes: CENTERED });
    await page.waitForFunction(() => !/STOPPED/.test(document.getElementById('send-state').textContent), null, { timeout: 2000 });
    await waitForStatus(page, 'the console sends again', (s) => s.operator_timeout === false, null, 2000);
    await driveForward(page);
    if (how === 'button') await page.click('#stop');
    else await page.keyboard.press('Space');
    await waitForStatus(page, `STOP (${how}) brought every wheel duty to 0`, wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
    const stopped = await latestStatus(page);
    assert.equal(stopped.targets.v1_radps, 0, 'no drive target after STOP');
    assert.match(await page.textContent('#send-state'), /STOPPED/);
    if (how === 'button') await screenshot(page, 'console-stopped.png');
  }
  // Centering the stick re-arms the console: pushing it drives again.
  await setPad(page, { axes: CENTERED });
  await page.waitForFunction(() => !/STOPPED/.test(document.getElementById('send-state').textContent), null, { timeout: 2000 });
  await driveForward(page);
  await setPad(page, { axes: CENTERED });
  assert.deepEqual(page.problems, []);
});

test('a second console is read-only until it takes control', async () => {
  const first = pages[1];  // in control, driving forward with the pad just centered
  const second = await open({ gamepad: true });
  await waitForLinkState(second, 'read-only', 5000);
  await waitForStatus(first, 'the rover stands still', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  assert.match(await second.textContent('#link-state'), /client \d+ controls/);
  // `marsokhod run` without --calibration: the driver runs on the configuration's values.
  assert.equal(await second.textContent('#calibration'), 'calibration: none (nominal configuration)');

  // Its stick pushed, the read-only console sends nothing; a gamepad message sent anyway is refused.
  await setPad(second, { axes: STICK_UP });
  assert.match(await second.textContent('#send-state'), /read-only/);
  await second.evaluate(() => window.marsokhod.link.sendInput({
    type: 'gamepad', axes: [0, -1, 0, 0], buttons: new Array(17).fill(false),
  }));
  await second.waitForFunction(() => /read-only: take control first/.test(
    document.getElementById('link-error').textContent), null, { timeout: 2000 });
  const still = await latestStatus(first);
  assert.ok(WHEELS.every((w) => Math.abs(still.motors[w].duty) < 0.05), 'a read-only console does not drive');

  await takeControl(second, { rearm: false });  // its stick is pushed
  await waitForLinkState(first, 'read-only', 2000);
  assert.match(await first.textContent('#link-error'), /lost control/);
  // The take-over stopped the rover, and the stop holds while the new controller's stick is
  // still pushed: it drives only after centring it.
  await new Promise((resolve) => setTimeout(resolve, 500));
  const held = await latestStatus(second);
  assert.equal(held.stop_latched, true, 'the take-over stop holds');
  assert.equal(held.targets.v1_radps, 0, 'no drive target with the stick pushed through a take-over');
  assert.match(await second.textContent('#stop-banner'), /took control/);
  await setPad(second, { axes: CENTERED });
  await waitForStatus(second, 'centring the stick re-armed', (s) => s.stop_latched === false, null, 2000);
  assert.equal(await second.isHidden('#stop-banner'), true);
  await setPad(second, { axes: STICK_UP });
  const from = (await latestStatus(second)).truth.position_m;
  await waitForStatus(second, 'the second console drives after take_control', (s, a) =>
    Math.hypot(s.truth.position_m[0] - a[0], s.truth.position_m[1] - a[1]) > a[2],
  [from[0], from[1], DRIVEN_M], MOVE_TIMEOUT_MS);
  await screenshot(second, 'console-second-in-control.png');
  await screenshot(first, 'console-first-lost-control.png');
  await setPad(second, { axes: CENTERED });
  assert.deepEqual(second.problems, []);
});

test('a STOP from another console holds, takes control away and is shown everywhere', async () => {
  const controller = pages[2];  // the second console holds control
  const other = pages[1];       // read-only
  await driveForward(controller);  // its stick stays pushed through what follows
  await other.click('#stop');
  await waitForStatus(other, 'the other console\'s STOP stopped every wheel', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  await waitForLinkState(controller, 'read-only', 2000);
  for (const page of [controller, other]) {
    await page.waitForFunction(() => /pressed STOP; client \d+ lost control/.test(
      document.getElementById('stop-banner').textContent), null, { timeout: 2000 });
  }
  await screenshot(controller, 'console-stopped-by-another.png');
  // Taking control back with the stick still pushed does not drive.
  await takeControl(controller, { rearm: false });
  await new Promise((resolve) => setTimeout(resolve, 500));
  const held = await latestStatus(controller);
  assert.equal(held.stop_latched, true);
  assert.ok(wheelsStill(held, STILL_DUTY), 'the pushed stick does not restart the rover');
  await setPad(controller, { axes: CENTERED });
  await waitForStatus(controller, 're-armed once centred', (s) => s.stop_latched === false, null, 2000);
  assert.deepEqual(controller.problems, []);
  assert.deepEqual(other.problems, []);
});

test('closing the controlling page stops the rover within 0.5 s plus a cycle', async (t) => {
  const controller = pages[2];  // the second console holds control
  const watcher = pages[0];     // read-only since the first test
  await driveForward(controller);
  await waitForStatus(watcher, 'the watcher sees the rover drive', wheelsDriveForward, null, 2000);
  // Judged in the server's own time, not the wall's: how long the browser takes to close a page
  // and this test to poll are not the rover's. The watcher keeps, in order, every status (its
  // mission time and drive target) and every stop it is told of.
  await watcher.evaluate(() => {
    window.__received = [];
    window.marsokhod.link.on('status', ({ status }) => window.__received.push(
      { t: status.mission_time_s, v1: status.targets.v1_radps }));
    window.marsokhod.link.on('stopped', ({ reason }) => window.__received.push({ stopped: reason }));
  });
  const closedAt = Date.now();
  await controller.context().close();
  pages.splice(2, 1);
  await waitForStatus(watcher, 'the drive target is zero after the controller left', (s) =>
    s.targets.v1_radps === 0, null, STOP_TIMEOUT_MS);
  await waitForStatus(watcher, 'every wheel duty reached 0', wheelsStill, STILL_DUTY, STOP_TIMEOUT_MS);
  const stillMs = Date.now() - closedAt;
  const received = await watcher.evaluate(() => window.__received);
  // The server saw the controller leave after its last status with the drive target on; the
  // first status with it zero may come at most the 0.5 s operator timeout, a control cycle and a
  // status period (0.05 s) later. A disconnect the server notices stops at once (a `stopped`).
  const stopAt = received.findIndex((e) => e.stopped !== undefined);
  // Statuses sent before the drive reached the server may still arrive first (v1 = 0): the zero
  // that counts is the first after a status with the target on.
  const onAt = received.findIndex((e) => e.v1 > 0);
  const zeroAt = onAt < 0 ? -1 : received.findIndex((e, i) => i > onAt && e.v1 === 0);
  assert.ok(zeroAt > 0, `the watcher saw the target on, then zero: ${JSON.stringify(received)}`);
  const lastOn = received.slice(0, zeroAt).findLast((e) => e.v1 !== undefined);
  assert.ok(lastOn !== undefined && lastOn.v1 > 0, `a status with the target on came first: ${JSON.stringify(received)}`);
  const serverMs = 1000 * (received[zeroAt].t - lastOn.t);
  assert.ok(serverMs <= 1000 * (0.5 + CYCLE_S + STATUS_PERIOD_S) + 1e-6,
    `target zero ${serverMs.toFixed(0)} ms of mission time after the last status with it on`);
  assert.ok(stopAt >= 0 && /client \d+/.test(received[stopAt].stopped),
    `the watcher was told of the stop: ${JSON.stringify(received)}`);
  await waitForLinkState(watcher, 'read-only', 1000);
  assert.match(await watcher.textContent('#link-state'), /nobody controls/);
  await screenshot(watcher, 'console-controller-closed.png');

  // Take control and give it back: nobody controls again.
  await takeControl(watcher);
  assert.equal(await watcher.isDisabled('#config-apply'), false, 'the controller may configure');
  await watcher.click('#release-control');
  await waitForLinkState(watcher, 'read-only', 2000);
  assert.match(await watcher.textContent('#link-state'), /nobody controls/);
  t.diagnostic(`target zero ${serverMs.toFixed(0)} ms of mission time after the last status with it on; duties zero after ${stillMs} ms of wall time`);
});

test('the token leaves the address bar, and the WebSocket needs the session', async () => {
  const page = pages[0];
  assert.equal(new URL(page.url()).searchParams.get('token'), null, 'the token left the address');
  const cookies = await page.context().cookies();
  const session = cookies.find((c) => c.name === `marsokhod_session_${server.port}`);
  assert.ok(session, 'a session cookie');
  assert.equal(session.httpOnly, true);
  assert.equal(session.sameSite, 'Strict');
  assert.equal(await page.evaluate(() => document.cookie), '', 'no script can read it');
});

test('a wrong token is refused', async () => {
  // The waits are for an answer, not a timing requirement: 10 s, because a headless page on a
  // loaded machine (the C++ tests beside it) once took longer than 3 s to show the refusal.
  // The server's answer itself: HTTP 401, no upgrade (before the page's try puts 127.0.0.1 into
  // the wrong-token back-off).
  const code = await new Promise((resolve, reject) => {
    const request = http.get({
      host: '127.0.0.1', port: server.port, path: '/ws', timeout: 10000,
      headers: { Connection: 'Upgrade', Upgrade: 'websocket', 'Sec-WebSocket-Version': '13',
        'Sec-WebSocket-Key': 'dGhlIHNhbXBsZSBub25jZQ==', Authorization: 'Bearer not-the-right-token-000' },
    }, (response) => { response.resume(); resolve(response.statusCode); });
    request.on('upgrade', () => resolve(101));
    request.on('timeout', () => request.destroy(new Error('no answer within 10 s')));
    request.on('error', reject);
  });
  assert.equal(code, 401);

  const wrong = server.url.replace(/token=[^&]+/, 'token=not-the-right-token-000');
  const page = await openConsole(browser, wrong);
  pages.push(page);
  await page.waitForFunction(() => /refused the token/.test(
    document.getElementById('link-error').textContent), null, { timeout: 10000 })
    .catch(async (err) => {
      throw new Error(`no refusal shown; #link-error: ${await page.textContent('#link-error')}`, { cause: err });
    });
  assert.equal(await page.isDisabled('#take-control'), true);
  await screenshot(page, 'console-wrong-token.png');

  const none = await openConsole(browser, server.url.replace(/\?.*$/, ''));
  pages.push(none);
  await none.waitForFunction(() => /no token in the page address/.test(
    document.getElementById('link-error').textContent), null, { timeout: 10000 });
});

test('the server exits cleanly on SIGTERM', async () => {
  const result = await server.stop();
  assert.deepEqual(result, { code: 0, signal: null }, `marsokhod run said:\n${server.output.text}`);
});
