// The console's pure parts, in node without a browser: the geometry of the 3-D view (values worked
// out by hand from a = 0.145 m, b = 0.413 m), the keyboard's synthetic gamepad, the gamepad
// reading, the `configure` message, the WebSocket address and the status' formatting.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { axleDistance, strutElevation, jointPosition, roverPose } from '../src/view3d.js';
import { keyboardReading } from '../src/keyboard.js';
import { readPad, firstStandardPad, mergeReadings, gamepadMessage, neutralReading } from '../src/gamepad.js';
import { configureMessage } from '../src/config.js';
import { websocketUrl, addressWithoutToken } from '../src/link.js';
import { missionTime, lcdDisplay } from '../src/status.js';

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
