// The console's pure parts, in node without a browser: the geometry of the 3-D view (values worked
// out by hand from a = 0.145 m, b = 0.413 m), the keyboard's synthetic gamepad, the gamepad
// reading, the `configure` message, the WebSocket address, the status' formatting, the map's
// transform, fit, grid and tracks, the mission form's messages and heartbeat, and velocity mode.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { axleDistance, strutElevation, jointPosition, roverPose, soilSurface, leastSquaresPlane } from '../src/view3d.js';
import { keyboardReading } from '../src/keyboard.js';
import {
  readPad, firstStandardPad, mergeReadings, gamepadMessage, neutralReading, applyDeadZone, DEAD_ZONE,
} from '../src/gamepad.js';
import { configureMessage, inForceLabels } from '../src/config.js';
import { websocketUrl, addressWithoutToken } from '../src/link.js';
import { missionTime, lcdDisplay } from '../src/status.js';
import {
  parseNumber, parseWaypoints, formatWaypoints, boundsOf, fitView, toScreen, toWorld, gridStep,
  pathLength, TrackLog, missionWaypoints, missionTarget, formatMetres,
} from '../src/map.js';
import { missionMessage, inputToSend, MissionWatch, missionSummary, PENDING_MS } from '../src/mission.js';
import { velocityLimits, stickVelocity, formVelocity, velocityStep, velocityText } from '../src/velocity.js';

const A = 0.145, B = 0.413;
const close = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual} is not ${expected} ± ${tolerance}`);

test('lever geometry: the joint vertical, straight, and at a right angle', () => {
  const vertical = Math.acos(A / B);  // Remark 3.1: 1.2121 rad
  close(vertical, 1.2121, 1e-4, 'vertical bend');
  close(axleDistance(vertical), Math.sqrt(B * B - A * A), 1e-12, 'c, lever hanging down');
  close(strutElevation(axleDistance(vertical)), 0.359, 5e-4, 'α, the table\'s maximum elevation');
  const [jx, jz] = jointPosition(Math.sqrt(B * B - A * A), 0);
  close(jx, Math.sqrt(B * B - A * A), 1e-12, 'joint straight above the exterior axle (x)');
  close(jz, A, 1e-12, 'joint a above the axles\' line (z)');
  close(axleDistance(Math.PI), A + B, 1e-12, 'c stretched straight');
  close(strutElevation(A + B), 0, 1e-6, 'α stretched straight');
  close(axleDistance(Math.PI / 2), Math.hypot(A, B), 1e-12, 'c at a right angle');
  const [rx, rz] = jointPosition(-Math.sqrt(B * B - A * A), 0);
  close(rx, -Math.sqrt(B * B - A * A), 1e-12, 'rear joint above its axle (x)');
  close(rz, A, 1e-12, 'rear joint above the axles\' line, not below (z)');
});

test('without truth the rover stands level at the origin with its joints at p6, p7', () => {
  const motors = { AF: { position_rad: -1.2121 }, AR: { position_rad: 2.0 }, FL: { position_rad: 0.5 } };
  const pose = roverPose({ motors });
  assert.equal(pose.source, 'joints');
  assert.deepEqual(pose.position.toArray(), [0, 0, 0.125]);
  assert.deepEqual([pose.rotation.x, pose.rotation.y, pose.rotation.z], [0, 0, 0]);
  close(pose.wheels[0].x, axleDistance(1.2121), 1e-12, 'FL ahead by c(γf = −p6)');
  close(pose.wheels[0].y, 0.35, 1e-12, 'FL on the left (+y), half the track');
  close(pose.wheels[5].x, -axleDistance(2.0), 1e-12, 'BR behind by c(γr = p7)');
  close(pose.wheels[5].y, -0.35, 1e-12, 'BR on the right');
  assert.deepEqual(pose.wheelAngles, [0.5, 0, 0, 0, 0, 0]);
  const empty = roverPose({});
  close(empty.wheels[0].x, Math.sqrt(B * B - A * A), 1e-12, 'no status: joints vertical');
});

test('with truth the wheels come back into the rover frame (yaw 90°: x → world y)', () => {
  const local = [[0.4, 0.35], [0.4, -0.35], [0, 0.35], [0, -0.35], [-0.4, 0.35], [-0.4, -0.35]];
  const truth = {
    position_m: [1, 2, 0.125],
    roll_pitch_yaw_rad: [0, 0, Math.PI / 2],
    joint_angle_rad: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, -1.5, 1.6],
    wheel_position_m: local.map(([x, y]) => [1 - y, 2 + x, 0.125]),
  };
  const pose = roverPose({ truth, motors: {} });
  assert.equal(pose.source, 'truth');
  pose.wheels.forEach((w, i) => {
    close(w.x, local[i][0], 1e-12, `wheel ${i} x`);
    close(w.y, local[i][1], 1e-12, `wheel ${i} y`);
    close(w.z, 0, 1e-12, `wheel ${i} z`);
  });
  assert.deepEqual(pose.wheelAngles, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]);
  const withAngles = roverPose({ truth: { ...truth, wheel_angle_rad: [1, 2, 3, 4, 5, 6] } });
  assert.deepEqual(withAngles.wheelAngles, [1, 2, 3, 4, 5, 6]);
  const broken = roverPose({ truth: { ...truth, position_m: [null, 2, 0] }, motors: {} });
  assert.equal(broken.source, 'joints', 'a truth with null (non-finite) values is not drawn');
});

test('the keyboard reads as a standard gamepad', () => {
  assert.deepEqual(keyboardReading(['KeyW'], false).axes, [0, -1, 0, 0], 'W: left stick up');
  assert.deepEqual(keyboardReading(['KeyS', 'KeyD'], false).axes, [1, 1, 0, 0]);
  assert.deepEqual(keyboardReading(['KeyW', 'KeyS'], false).axes, [0, 0, 0, 0], 'opposite keys cancel');
  assert.deepEqual(keyboardReading(['KeyW', 'ArrowRight'], true).axes, [0, -0.5, 0.5, 0], 'shift: half');
  const pressed = (codes) => keyboardReading(codes, false).buttons
    .flatMap((down, i) => (down ? [i] : []));
  assert.deepEqual(pressed(['KeyQ', 'KeyZ', 'KeyE', 'KeyC']), [4, 5, 6, 7]);
  assert.deepEqual(pressed(['KeyF', 'KeyR']), [0, 2], 'R, F: X, A (sideways drift m3)');
  assert.deepEqual(pressed(['Digit1', 'Digit2', 'Digit3', 'Digit4']), [12, 13, 14, 15]);
  assert.deepEqual(pressed(['Digit5', 'Digit0', 'KeyP']), [1, 3, 8]);
  assert.deepEqual(pressed(['KeyX', 'Enter']), [], 'unmapped keys do nothing');
});

test('gamepad readings: standard pads only, clamped, merged with the keyboard', () => {
  const other = { mapping: '', axes: [0, -1, 0, 0], buttons: [] };
  const pad = {
    mapping: 'standard', connected: true, axes: [1.0000001, NaN, -0.5, 0, 0.9],
    buttons: Array.from({ length: 18 }, (_, i) => ({ pressed: i === 12 || i === 17 })),
  };
  assert.equal(firstStandardPad([null, other, pad]), pad);
  assert.equal(firstStandardPad([other]), null);
  const reading = readPad(pad);
  assert.deepEqual(reading.axes, [1, 0, -0.5, 0], '4 axes, clamped to ±1, NaN centered');
  assert.equal(reading.buttons.length, 17);
  assert.deepEqual(reading.buttons.flatMap((b, i) => (b ? [i] : [])), [12]);
  const keys = keyboardReading(['KeyW', 'KeyQ'], false);
  const merged = mergeReadings(reading, keys);
  assert.deepEqual(merged.axes, [1, -1, -0.5, 0]);
  assert.deepEqual(merged.buttons.flatMap((b, i) => (b ? [i] : [])), [4, 12]);
  assert.deepEqual(mergeReadings(null, keys), keys);
  const message = gamepadMessage(neutralReading());
  assert.deepEqual(Object.keys(message), ['type', 'axes', 'buttons']);
  assert.equal(message.type, 'gamepad');
  assert.equal(message.axes.length, 4);
  assert.equal(message.buttons.length, 17);
});

test('configure sends only what was set, and refuses values out of range', () => {
  const blank = {
    max_drop_v: '', load_distribution: '', speed_scale: '',
    power_management: '', slant_response: '', contract_on_turn: '', axle_placement: '',
  };
  assert.deepEqual(configureMessage(blank), { message: { type: 'configure' } });
  assert.deepEqual(configureMessage({ ...blank, max_drop_v: '1.5', load_distribution: 's', slant_response: 'off', speed_scale: '0' }),
    { message: { type: 'configure', max_drop_v: 1.5, load_distribution: 's', behaviours: { slant_response: false }, speed_scale: 0 } });
  assert.match(configureMessage({ ...blank, max_drop_v: '0' }).error, /^Υ: 0 is out of range; allowed \(0, 10\] V$/);
  assert.match(configureMessage({ ...blank, speed_scale: '1.5' }).error, /out of range; allowed 0\.\.1/);
  assert.match(configureMessage({ ...blank, speed_scale: 'fast' }).error, /out of range/);
  assert.deepEqual(configureMessage({ ...blank, supply: 'tether' }), { message: { type: 'configure', supply: 'tether' } });
  assert.match(configureMessage({ ...blank, supply: 'mains' }).error, /^supply: mains is not one of battery, tether$/);
});

test('every configuration field names the setting in force, "unchanged" before the first status', () => {
  const settings = {
    max_drop_v: 2.5, load_distribution: 'v', speed_scale: 0.75, supply: 'tether',
    behaviours: { power_management: true, slant_response: false, contract_on_turn: true, axle_placement: false },
  };
  assert.deepEqual(inForceLabels(settings), {
    max_drop_v: '2.5 (in force)', load_distribution: 'hᵛ (6.5) (in force)', speed_scale: '0.75 (in force)',
    power_management: 'on (in force)', slant_response: 'off (in force)', contract_on_turn: 'on (in force)',
    axle_placement: 'off (in force)', supply: 'tether (in force)',
  });
  assert.deepEqual(Object.values(inForceLabels(undefined)), Array(8).fill('unchanged'));
});

test('the WebSocket address sits next to the page and never carries the token', () => {
  const at = (href) => ({ href, protocol: new URL(href).protocol });
  assert.equal(websocketUrl(at('http://127.0.0.1:8080/?token=abc')), 'ws://127.0.0.1:8080/ws');
  assert.equal(websocketUrl(at('https://rover.example/?token=x#plots')), 'wss://rover.example/ws');
  assert.equal(websocketUrl(at('http://h/rover/index.html?token=t')), 'ws://h/rover/ws');
});

test('the token leaves the address, the rest of it stays', () => {
  assert.equal(addressWithoutToken('http://h:8080/?token=abc'), '/');
  assert.equal(addressWithoutToken('http://h/rover/?a=1&token=abc&b=2#plots'), '/rover/?a=1&b=2#plots');
});

test('mission time reads like Figure 8.1: minutes, seconds, milliseconds', () => {
  assert.equal(missionTime(47 * 60 + 12.037), '47:12.037');
  assert.equal(missionTime(3601.5), '1:00:01.500');
  assert.equal(missionTime(0), '00:00.000');
  assert.equal(missionTime(null), '–');
});

test('lcdDisplay: the driver\'s eight characters, then the voltage as µ8 shows it', () => {
  // src/driver/lcd.hpp's layout and src/sim/firmware/sensor_controller.cpp's "%7.2fV".
  assert.equal(lcdDisplay('   -2.5d', 24.1), '   -2.5d  24.10V');
  assert.equal(lcdDisplay('TO +0.0d', 24.5673), 'TO +0.0d  24.57V');
  assert.equal(lcdDisplay(undefined, null), '              –V');
  assert.equal(lcdDisplay('short', 9.5), 'short      9.50V');
});

test('numbers as people type them, and nothing else', () => {
  assert.equal(parseNumber(' 1.5 '), 1.5);
  assert.equal(parseNumber('-0.25'), -0.25);
  assert.equal(parseNumber('+.5'), 0.5);
  assert.equal(parseNumber('2e-1'), 0.2);
  assert.equal(parseNumber('3.'), 3);
  for (const bad of ['', ' ', 'abc', '1,5', '0x10', 'Infinity', 'NaN', '1e', '--1', '1 2']) {
    assert.equal(parseNumber(bad), null, `"${bad}" is not a number`);
  }
});

test('waypoints typed as "x,y; x,y"', () => {
  assert.deepEqual(parseWaypoints('2,0; 2,2'), { waypoints: [{ x: 2, y: 0 }, { x: 2, y: 2 }] });
  assert.deepEqual(parseWaypoints(' -1.5 , .5 ;\n3,4;'), { waypoints: [{ x: -1.5, y: 0.5 }, { x: 3, y: 4 }] },
    'spaces, new lines and a trailing separator');
  assert.match(parseWaypoints('').error, /^no waypoints/);
  assert.match(parseWaypoints('  ;  ').error, /^no waypoints/);
  assert.equal(parseWaypoints('1,2;;3,4').error, 'waypoint 2: "" is not x,y (two numbers in metres)');
  assert.equal(parseWaypoints('1,2; 3').error, 'waypoint 2: "3" is not x,y (two numbers in metres)');
  assert.equal(parseWaypoints('1,2,3').error, 'waypoint 1: "1,2,3" is not x,y (two numbers in metres)');
  assert.equal(parseWaypoints('1,NaN').error, 'waypoint 1: "1,NaN" is not x,y (two numbers in metres)');
  assert.equal(parseWaypoints('1,x').error, 'waypoint 1: "1,x" is not x,y (two numbers in metres)');
  assert.equal(parseWaypoints('0,0; 1001,0').error, 'waypoint 2: 1001,0 is 1001.0 m from the origin; at most 1000 m');
  assert.equal(parseWaypoints('800,-600').waypoints.length, 1, '1000 m from the origin: allowed');
  assert.equal(parseWaypoints('800,-600.5').error, 'waypoint 1: 800,-600.5 is 1000.3 m from the origin; at most 1000 m');
  assert.equal(parseWaypoints('1,1;2,2;3,3', { max: 2 }).error, '3 waypoints; at most 2');
  assert.equal(parseWaypoints(Array(64).fill('1,1').join(';')).waypoints.length, 64);
  assert.equal(parseWaypoints(Array(65).fill('1,1').join(';')).error, '65 waypoints; at most 64');
  assert.equal(formatWaypoints([{ x: 1.234, y: -0.5 }, { x: 2, y: 0.005 }]), '1.23,-0.5; 2,0.01');
  assert.deepEqual(parseWaypoints(formatWaypoints([{ x: 1.25, y: -3 }])).waypoints, [{ x: 1.25, y: -3 }]);
});

test('the map fits its points with the same scale both ways, x right and y up', () => {
  const b = boundsOf([{ x: 0, y: 0 }, { x: 4, y: 1 }, { x: 2, y: -1 }, { x: NaN, y: 9 }]);
  assert.deepEqual(b, { minX: 0, maxX: 4, minY: -1, maxY: 1 }, 'non-finite points left out');
  assert.equal(boundsOf([]), null);
  // 4 m × 2 m into 420 × 320 px with 10 px margins: x limits, 400/4 = 100 px/m; the centre
  // (2, 0) in the middle (210, 160).
  const t = fitView(b, 420, 320, { margin: 10, minSpan: 1 });
  assert.equal(t.scale, 100);
  assert.deepEqual(toScreen(t, { x: 2, y: 0 }), { x: 210, y: 160 });
  assert.deepEqual(toScreen(t, { x: 0, y: 1 }), { x: 10, y: 60 }, 'left edge; y up is up the screen');
  assert.deepEqual(toScreen(t, { x: 4, y: -1 }), { x: 410, y: 260 });
  assert.deepEqual(toWorld(t, { x: 410, y: 260 }), { x: 4, y: -1 }, 'toWorld undoes toScreen');
  // A tall box: y limits. 1 m × 6 m into 420 × 320: (320 − 20)/6 = 50 px/m.
  const tall = fitView({ minX: 0, maxX: 1, minY: 0, maxY: 6 }, 420, 320, { margin: 10, minSpan: 1 });
  assert.equal(tall.scale, 50);
  assert.deepEqual(toScreen(tall, { x: 0.5, y: 6 }), { x: 210, y: 10 });
  // A single point (the rover standing): at least minSpan across, centred on it.
  const one = fitView({ minX: 3, maxX: 3, minY: 3, maxY: 3 }, 420, 320, { margin: 10, minSpan: 2 });
  assert.equal(one.scale, 150);
  assert.deepEqual(toScreen(one, { x: 3, y: 3 }), { x: 210, y: 160 });
  const none = fitView(null, 420, 320, { margin: 10, minSpan: 2 });
  assert.deepEqual(toScreen(none, { x: 0, y: 0 }), { x: 210, y: 160 }, 'nothing to show: the origin in the middle');
});

test('the grid steps 1-2-5 metres, at least 40 px apart', () => {
  assert.equal(gridStep(100), 0.5);    // 0.4 m needed
  assert.equal(gridStep(40), 1);       // exactly 1 m
  assert.equal(gridStep(30), 2);       // 1.33 m needed
  assert.equal(gridStep(10), 5);       // 4 m needed
  assert.equal(gridStep(5), 10);       // 8 m needed
  assert.equal(gridStep(1000), 0.05);  // 0.04 m needed
  assert.equal(formatMetres(2), '2 m');
  assert.equal(formatMetres(0.5), '50 cm');
  assert.equal(formatMetres(0.005), '5 mm');
});

test('tracks grow by points 5 mm apart and start again with a new driver frame', () => {
  const log = new TrackLog({ minStep: 0.005, maxPoints: 1000 });
  const status = (t, x, y, distance, truth) => ({
    mission_time_s: t, pose: { x_m: x, y_m: y, distance_m: distance },
    ...(truth ? { truth: { odometry: { x_m: truth[0], y_m: truth[1], heading_rad: 0 } } } : {}),
  });
  assert.equal(log.add(status(1, 0, 0, 0)), false);
  log.add(status(1.05, 0.003, 0, 0.003));  // 3 mm from the last point: not kept
  log.add(status(1.1, 0.3, 0.4, 0.5, [0.31, 0.41]));
  log.add(status(1.15, 0.6, 0.8, 1.0, [0.62, 0.82]));
  assert.deepEqual(log.estimated, [{ x: 0, y: 0 }, { x: 0.3, y: 0.4 }, { x: 0.6, y: 0.8 }]);
  assert.equal(pathLength(log.estimated), 1.0);
  assert.deepEqual(log.truth, [{ x: 0.31, y: 0.41 }, { x: 0.62, y: 0.82 }], 'the truth only where present');
  log.add(status(1.2, 0.6, 0.8, 1.0, [null, 0.8]));
  assert.equal(log.truth.length, 2, 'a non-finite truth is left out');
  // The distance going back: a restarted driver's frame. Both tracks start afresh.
  assert.equal(log.add(status(1.25, 0, 0, 0, [0, 0])), true);
  assert.deepEqual(log.estimated, [{ x: 0, y: 0 }]);
  assert.deepEqual(log.truth, [{ x: 0, y: 0 }]);
  assert.equal(log.frames, 2);
  log.add(status(1.3, 1, 0, 1));
  // The mission time going back, though the distance did not (a restart that already drove).
  assert.equal(log.add(status(0.5, 2, 0, 2)), true);
  assert.deepEqual(log.estimated, [{ x: 2, y: 0 }]);
  // A missing pose leaves the track as it is.
  assert.equal(log.add({ mission_time_s: 0.6 }), false);
  assert.equal(log.estimated.length, 1);
  log.clear();
  assert.deepEqual([log.estimated, log.truth], [[], []]);
  // A long track is thinned to half, its first and last points kept.
  const small = new TrackLog({ minStep: 0, maxPoints: 4 });
  for (let i = 0; i <= 4; i += 1) small.add(status(i, i, 0, i));
  assert.deepEqual(small.estimated.map((p) => p.x), [0, 2, 4]);
});

test('the mission\'s waypoints and target on the map', () => {
  const goto = { id: 2, kind: 'goto', state: 'running', leg: 1, waypoints: [[2, 0], [2, 2], [null, 1]] };
  assert.deepEqual(missionWaypoints(goto), [{ x: 2, y: 0 }, { x: 2, y: 2 }]);
  assert.deepEqual(missionTarget(goto), { x: 2, y: 2 }, 'goto: the waypoint of the leg');
  assert.deepEqual(missionTarget({ ...goto, kind: 'move', waypoints: [[0.3, 0]] }), { x: 0.3, y: 0 });
  assert.equal(missionTarget({ ...goto, kind: 'turn', waypoints: [] }), null);
  assert.equal(missionTarget({ ...goto, state: 'reached' }), null, 'no target once reached');
  assert.deepEqual(missionWaypoints(undefined), []);
});

test('mission messages from the form, and what it refuses', () => {
  const turn = missionMessage('turn', '90');
  assert.equal(turn.message.kind, 'turn');
  close(turn.message.angle_rad, Math.PI / 2, 1e-15, '90° in radians');
  close(missionMessage('turn', '-45').message.angle_rad, -Math.PI / 4, 1e-15, '−45°: clockwise');
  assert.deepEqual(missionMessage('move', '-0.3'), { message: { type: 'mission', kind: 'move', distance_m: -0.3 } });
  assert.deepEqual(missionMessage('goto', '2,0; 2,2'), {
    message: { type: 'mission', kind: 'goto', waypoints: [{ x_m: 2, y_m: 0 }, { x_m: 2, y_m: 2 }] },
  });
  assert.equal(missionMessage('turn', '').error, 'turn: empty; type a number in °');
  assert.equal(missionMessage('turn', 'left').error, 'turn: "left" is not a number (°)');
  assert.equal(missionMessage('turn', '800').error, 'turn: 800 is out of range; allowed −720..720 °');
  close(missionMessage('turn', '-720').message.angle_rad, -4 * Math.PI, 1e-14, 'two turns clockwise');
  assert.equal(missionMessage('move', '0').error, 'move: 0 m does nothing');
  assert.equal(missionMessage('move', 'NaN').error, 'move: "NaN" is not a number (m)');
  assert.equal(missionMessage('move', '-101').error, 'move: -101 is out of range; allowed −100..100 m');
  assert.match(missionMessage('goto', '').error, /^go to: no waypoints/);
  assert.match(missionMessage('goto', '1;2').error, /^go to: waypoint 1: "1" is not x,y/);
  // The standing after each leg: blank sends none, else 0 < s ≤ 60 for any kind.
  assert.deepEqual(missionMessage('goto', '2,0', '9'), {
    message: { type: 'mission', kind: 'goto', waypoints: [{ x_m: 2, y_m: 0 }], settle_s: 9 },
  });
  assert.equal(missionMessage('move', '1', ' 60 ').message.settle_s, 60);
  assert.equal(missionMessage('turn', '90', '0.5').message.settle_s, 0.5);
  assert.equal('settle_s' in missionMessage('move', '1', '  ').message, false, 'blank: none');
  assert.equal(missionMessage('move', '1', '0').error,
    'stand: 0 s is out of range; allowed 0 < s ≤ 60 s (blank: the configured one)');
  assert.match(missionMessage('move', '1', '61').error, /^stand: 61 s is out of range/);
  assert.equal(missionMessage('move', '1', 'long').error, 'stand: "long" is not a number (s)');
});

test('while a mission runs and the sticks rest, a heartbeat at 20 Hz replaces the reading', () => {
  const sends = (state) => [0, 1, 2, 3].map((tick) => inputToSend({ ...state, tick }));
  assert.deepEqual(sends({ missionActive: false, neutral: true, stopLatched: false }),
    ['gamepad', 'gamepad', 'gamepad', 'gamepad'], 'no mission: the reading at 20 Hz');
  assert.deepEqual(sends({ missionActive: true, neutral: true, stopLatched: false }),
    ['heartbeat', 'heartbeat', 'heartbeat', 'heartbeat'], 'every 50 ms tick: 20 Hz');
  assert.deepEqual(sends({ missionActive: true, neutral: false, stopLatched: false }),
    ['gamepad', 'gamepad', 'gamepad', 'gamepad'], 'a pushed stick takes over');
  assert.deepEqual(sends({ missionActive: true, neutral: true, stopLatched: true }),
    ['gamepad', 'gamepad', 'gamepad', 'gamepad'], 'after STOP: the neutral reading');
});

test('a mission counts as running from its sending until the status shows how it went', () => {
  const watch = new MissionWatch();
  const idle = { id: 3, kind: 'move', state: 'reached' };
  assert.equal(watch.active(idle, 0), false);
  watch.sent(3, 1000);
  assert.equal(watch.active(idle, 1050), true, 'sent, not yet in the status');
  assert.equal(watch.active({ ...idle, id: 4, state: 'running' }, 1100), true);
  assert.equal(watch.active({ ...idle, id: 4, state: 'reached' }, 1200), false, 'reached');
  watch.sent(4, 2000);
  assert.equal(watch.active({ ...idle, id: 5, state: 'aborted' }, 2050), false, 'refused or aborted at once');
  watch.sent(5, 3000);
  assert.equal(watch.active(undefined, 3000 + PENDING_MS - 1), true);
  assert.equal(watch.active(undefined, 3000 + PENDING_MS), false, 'a server without missions never shows it');
  watch.sent(5, 4000);
  watch.cancel();
  assert.equal(watch.active(undefined, 4001), false, 'Stop mission');
});

test('the mission\'s status in one line', () => {
  assert.match(missionSummary(undefined), /^no mission support/);
  assert.equal(missionSummary({ id: 0, kind: 'none', state: 'idle' }), 'no mission yet');
  assert.equal(missionSummary({
    id: 3, kind: 'goto', state: 'running', reason: '', progress: 0.42, leg: 1,
    waypoints: [[2, 0], [2, 2]], target_heading_rad: 1.57, remaining_m: 1.2, remaining_rad: null,
  }), '#3 goto · running · leg 2 of 2 · 42 % · 1.20 m to go');
  assert.equal(missionSummary({
    id: 3, kind: 'goto', state: 'running', reason: '', progress: 0.42, leg: 1,
    waypoints: [[2, 0], [2, 2]], target_heading_rad: 1.57, remaining_m: 1.2, remaining_rad: null,
    settle_s: 9,
  }), '#3 goto · running · leg 2 of 2 · 42 % · 1.20 m to go · stands 9 s a leg');
  assert.equal(missionSummary({
    id: 4, kind: 'turn', state: 'running', progress: 0.5, leg: 0, waypoints: [],
    remaining_m: null, remaining_rad: Math.PI / 4,
  }), '#4 turn · running · 50 % · 45.0° to turn');
  assert.equal(missionSummary({
    id: 5, kind: 'move', state: 'aborted', reason: 'the operator fell silent for 0.5 s', progress: 0.1,
    leg: 0, waypoints: [[1, 0]], remaining_m: 0.9,
  }), '#5 move · aborted · 10 %');
  assert.equal(missionSummary({
    id: 6, kind: 'goto', state: 'reached', progress: 1, leg: 1, waypoints: [[1, 0], [1, 1]],
    remaining_m: null, remaining_rad: null, corrections: 1, settle_s: 4.5,
  }), '#6 goto · reached · leg 2 of 2 · 100 % · 1 correction');
});

// The default configuration's limits as the server's hello tells them (docs/operator-protocol.md):
// r·v1ᵈ = 0.125 m · 2.25 rad/s, r·v2ᵈ/(t/2) = 0.125 m · 1.5 rad/s / 0.35 m.
const LIMITS = { v_mps: 0.125 * 2.25, yaw_radps: 0.125 * 1.5 / 0.35 };
const pad = (axes) => ({ axes, buttons: new Array(17).fill(false) });

test('the dead zone is the server\'s: 0 inside 0.1, rescaled to reach ±1, continuous at its edge', () => {
  assert.equal(DEAD_ZONE, 0.1);
  assert.equal(applyDeadZone(0), 0);
  assert.equal(applyDeadZone(0.09), 0);
  assert.equal(applyDeadZone(-0.1), 0, 'its edge reads 0 from both sides');
  close(applyDeadZone(0.1 + 1e-9), 0, 1e-8, 'just outside');
  close(applyDeadZone(0.55), 0.5, 1e-12, '(0.55 − 0.1)/0.9');
  assert.equal(applyDeadZone(1), 1);
  assert.equal(applyDeadZone(-1), -1);
  assert.equal(applyDeadZone(Number.NaN), 0, 'a broken axis is no input');
});

test('velocity mode: the left stick × the server\'s limits, with the gamepad\'s dead zone and clipping', () => {
  assert.deepEqual(velocityLimits({ v_mps: 0.28125, yaw_radps: 0.5 }), { v_mps: 0.28125, yaw_radps: 0.5 });
  for (const bad of [undefined, null, 3, {}, { v_mps: 0.2 }, { v_mps: 0, yaw_radps: 0.5 }, { v_mps: -1, yaw_radps: 1 },
    { v_mps: Infinity, yaw_radps: 1 }, { v_mps: '0.2', yaw_radps: 1 }]) {
    assert.equal(velocityLimits(bad), null, `no limits from ${JSON.stringify(bad)}`);
  }
  assert.deepEqual(stickVelocity(pad([0, -1, 0, 0]), LIMITS), { v_mps: LIMITS.v_mps, yaw_radps: 0 }, 'full forward = the largest speed');
  assert.deepEqual(stickVelocity(pad([0, 1, 0, 0]), LIMITS), { v_mps: -LIMITS.v_mps, yaw_radps: 0 }, 'full back');
  assert.deepEqual(stickVelocity(pad([-1, 0, 0, 0]), LIMITS), { v_mps: 0, yaw_radps: LIMITS.yaw_radps },
    'stick left = counter-clockwise = + yaw (docs/gamepad.md: right is clockwise)');
  assert.deepEqual(stickVelocity(pad([0.09, -0.09, 1, -1]), LIMITS), { v_mps: 0, yaw_radps: 0 },
    'inside the dead zone: zero; the right stick does nothing');
  const half = stickVelocity(pad([0.55, -0.55, 0, 0]), LIMITS);
  close(half.v_mps, 0.5 * LIMITS.v_mps, 1e-12, 'half way past the dead zone: half speed');
  close(half.yaw_radps, -0.5 * LIMITS.yaw_radps, 1e-12, 'clockwise');
  assert.deepEqual(stickVelocity(pad([3, -7, 0, 0]), LIMITS), { v_mps: LIMITS.v_mps, yaw_radps: -LIMITS.yaw_radps },
    'clipped to the limits, which the server would otherwise reject');
  assert.ok(!Object.is(stickVelocity(pad([0, 0, 0, 0]), LIMITS).v_mps, -0), 'no −0 in the message');
  // The keyboard's W is the stick full up, Shift+W half of it (keyboard.js).
  assert.deepEqual(stickVelocity(keyboardReading(['KeyW', 'KeyA'], false), LIMITS),
    { v_mps: LIMITS.v_mps, yaw_radps: LIMITS.yaw_radps });
  close(stickVelocity(keyboardReading(['KeyW'], true), LIMITS).v_mps, (0.5 - 0.1) / 0.9 * LIMITS.v_mps, 1e-12, 'Shift+W');
});

test('the velocity form refuses bad input with a message and keeps 0 for one of v, ω', () => {
  assert.deepEqual(formVelocity('0.1', '0', LIMITS), { command: { v_mps: 0.1, yaw_radps: 0 } });
  assert.deepEqual(formVelocity(' -0.2 ', '0.3', LIMITS), { command: { v_mps: -0.2, yaw_radps: 0.3 } });
  assert.deepEqual(formVelocity('0', '-0.5', LIMITS), { command: { v_mps: 0, yaw_radps: -0.5 } }, 'on the spot');
  assert.equal(formVelocity('0.3', '0', LIMITS).error, 'v: 0.3 is out of range; allowed −0.281..0.281 m/s');
  assert.equal(formVelocity('0.1', '0.6', LIMITS).error, 'ω: 0.6 is out of range; allowed −0.535..0.535 rad/s');
  assert.equal(formVelocity('', '0', LIMITS).error, 'v: empty; type a number in m/s');
  assert.equal(formVelocity('fast', '0', LIMITS).error, 'v: "fast" is not a number (m/s)');
  assert.equal(formVelocity('0.1', 'NaN', LIMITS).error, 'ω: "NaN" is not a number (rad/s)');
  assert.equal(formVelocity('0', '0', LIMITS).error, 'v and ω are both 0: that is "stop"');
  assert.match(formVelocity('0.1', '0', null).error, /does not tell its velocity limits/);
  assert.equal(velocityText({ v_mps: 0.1, yaw_radps: -0.2 }), 'v 0.100 m/s, ω -0.200 rad/s');
});

test('velocity mode sends the stick, else the form\'s velocity until a stick takes over, else zero', () => {
  const centred = pad([0, 0, 0, 0]);
  const form = { v_mps: 0.1, yaw_radps: 0 };
  const zero = { type: 'velocity', v_mps: 0, yaw_radps: 0 };
  assert.deepEqual(velocityStep({ reading: centred, limits: LIMITS, held: null, drivingMission: false }),
    { message: zero, held: null, source: 'neutral' }, 'neutral: zero velocity, the driver stops the rover');
  assert.deepEqual(velocityStep({ reading: centred, limits: LIMITS, held: form, drivingMission: false }),
    { message: { type: 'velocity', ...form }, held: form, source: 'form' }, 'the form\'s velocity, kept');
  assert.deepEqual(velocityStep({ reading: pad([0, 0.5, 0, 0]), limits: LIMITS, held: form, drivingMission: false }),
    { message: { type: 'velocity', ...stickVelocity(pad([0, 0.5, 0, 0]), LIMITS) }, held: null, source: 'stick' },
    'a pushed stick takes over and ends the form\'s velocity');
  assert.deepEqual(velocityStep({ reading: centred, limits: LIMITS, held: null, drivingMission: true }),
    { message: { type: 'heartbeat' }, held: null, source: 'mission' }, 'a turn/move/goto is kept alive, not replaced');
  assert.equal(velocityStep({ reading: centred, limits: LIMITS, held: form, drivingMission: true }).source, 'form',
    'a velocity sent from the form replaces the mission');
});

test('a running velocity mission is not one the heartbeat keeps alive, and its line shows its values', () => {
  const watch = new MissionWatch();
  const running = { id: 7, kind: 'velocity', state: 'running', reason: '', progress: 0, leg: 0, waypoints: [],
    target_heading_rad: null, remaining_m: null, remaining_rad: null };
  assert.equal(watch.active(running, 0), false, 'else a neutral stick would send heartbeats that keep it going');
  assert.equal(watch.active({ ...running, kind: 'move' }, 0), true);
  assert.equal(missionSummary(running, { sent: { v_mps: 0.1, yaw_radps: 0 }, pose: { speed_mps: 0.0981, yaw_rate_radps: -0.0004 } }),
    '#7 velocity · running · sent v 0.100 m/s, ω 0.000 rad/s · estimated 0.098 m/s, -0.000 rad/s');
  assert.equal(missionSummary(running), '#7 velocity · running', 'another console\'s velocity: no values sent from here');
  assert.equal(missionSummary({ ...running, state: 'aborted', reason: 'the operator\'s input is no longer a velocity' }),
    '#7 velocity · aborted');
});

test('the soil patch: a vertex at each sample, two upward triangles a square, bad patches refused', () => {
  // 3 columns × 2 rows at 4 cm from (1.0, −0.5); a rut of 25 mm at row 1, column 1.
  const patch = { origin_m: [1.0, -0.5], cell_m: 0.04, columns: 3, rows: 2, height_mm: [0, 0, 0, 0, -25, 0] };
  const surface = soilSurface(patch);
  assert.ok(surface);
  assert.equal(surface.positions.length, 6 * 3);
  close(surface.positions[4 * 3], 1.04, 1e-6, 'x of row 1, column 1');
  close(surface.positions[4 * 3 + 1], -0.46, 1e-6, 'y of row 1, column 1');
  close(surface.positions[4 * 3 + 2], -0.025, 1e-7, 'the rut, in metres');
  close(surface.positions[2 * 3], 1.08, 1e-6, 'x of the last column');
  assert.equal(surface.indices.length, 2 * 6);  // (3 − 1)·(2 − 1) squares
  // Each triangle turns counter-clockwise seen from above: its normal points up (+z).
  for (let t = 0; t < surface.indices.length; t += 3) {
    const [a, b, c] = [0, 1, 2].map((i) => surface.indices[t + i]);
    const p = (/** @type {number} */ k) => [surface.positions[3 * k], surface.positions[3 * k + 1]];
    const [pa, pb, pc] = [p(a), p(b), p(c)];
    const cross = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
    assert.ok(cross > 0, `triangle ${t / 3} faces down`);
  }
  // The rut is darker than the level sand around it, and lies the deepest below the patch's
  // least-squares plane: by symmetry the plane is level along x and fits each row's mean, 0 and
  // −25/3 mm, so the rut lies 25 − 25/3 = 16.67 mm below it.
  assert.ok(surface.colors[4 * 3] < surface.colors[0], 'the rut is shaded darker');
  close(surface.lowestReliefM, -0.025 * 2 / 3, 1e-6, 'the rut below the plane');
  assert.equal(soilSurface(undefined), null);
  assert.equal(soilSurface({ ...patch, height_mm: [0, 0, 0] }), null, 'too few heights');
  assert.equal(soilSurface({ ...patch, rows: 1, height_mm: [0, 0, 0] }), null, 'one row is no surface');
  assert.equal(soilSurface({ ...patch, height_mm: [0, 0, 0, 0, null, 0] }), null, 'a height that is not a number');
  assert.equal(soilSurface({ ...patch, cell_m: 0 }), null, 'no cell size');
  assert.equal(soilSurface({ ...patch, columns: 2.5 }), null, 'a fractional size');
});

test('the soil patch\'s reference plane: a slope is found exactly, a rut does not tilt it much', () => {
  // z = 0.3 + 0.2·x − 0.1·y on a 5 × 4 grid.
  const points = [];
  for (let r = 0; r < 4; ++r) for (let c = 0; c < 5; ++c) points.push(c * 0.5, r * 0.5 - 1, 0.3 + 0.2 * c * 0.5 - 0.1 * (r * 0.5 - 1));
  const [a, b, cc] = leastSquaresPlane(new Float32Array(points));
  close(a, 0.3, 1e-6, 'a'); close(b, 0.2, 1e-6, 'b'); close(cc, -0.1, 1e-6, 'c');
  // One line of points: no plane, the mean height.
  assert.deepEqual(leastSquaresPlane(new Float32Array([0, 0, 1, 1, 0, 3])).map((v) => Math.round(v * 1e6) / 1e6), [2, 0, 0]);
});
