// The link server's Foxglove WebSocket (/foxglove, foxglove.websocket.v1) with npm's
// @foxglove/ws-protocol client — the protocol library Foxglove itself uses — against the real
// server: `marsokhod run`, the simulator, the driver and the link in one process, in real time.
// Connect with the token in the URL as Foxglove's connection dialog does, get the channels and
// their schemas, subscribe, receive the status with the fields its schema names, see the mission
// time advance, read the settings as parameters (and be refused setting them). Every wait is
// bounded and waits for a condition, never for a fixed time.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import wsProtocol from '@foxglove/ws-protocol';
import WebSocket from 'ws';

const { FoxgloveClient } = wsProtocol;  // a CommonJS package
import { startServer, REPO_DIR, SERVER_BIN } from './harness.mjs';

const TOKEN = 'foxglove-test-token-0123456789';
const WAIT_MS = 10000;
const TOPICS = ['/can/decoded', '/can/raw', '/imu', '/joint_states', '/pose', '/pose/estimate',
  '/status', '/tf', '/tf/links'];

let server;
let client;
let url;
const channels = new Map();  // topic → channel
const received = new Map();  // subscription id → [{ time, value }]
const times = [];
const statuses = [];
const parameterValues = [];
let serverInfo = null;
const decoder = new TextDecoder();

// Resolves when `predicate()` holds, checked on every event from the server; rejects after
// WAIT_MS naming `what`.
function until(what, predicate) {
  return new Promise((resolve, reject) => {
    const check = () => {
      if (!predicate()) return false;
      clearTimeout(timer);
      for (const e of EVENTS) client.off(e, check);
      resolve();
      return true;
    };
    const timer = setTimeout(() => {
      for (const e of EVENTS) client.off(e, check);
      reject(new Error(`timed out after ${WAIT_MS} ms waiting until ${what}`));
    }, WAIT_MS);
    if (check()) return;
    for (const e of EVENTS) client.on(e, check);
  });
}
const EVENTS = ['serverInfo', 'advertise', 'message', 'time', 'status', 'parameterValues'];

function connect(address) {
  const ws = new WebSocket(address, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const c = new FoxgloveClient({ ws });
  c.on('serverInfo', (info) => { serverInfo = info; });
  c.on('advertise', (list) => { for (const ch of list) channels.set(ch.topic, ch); });
  c.on('message', ({ subscriptionId, timestamp, data }) => {
    const list = received.get(subscriptionId) ?? [];
    list.push({ time: timestamp, value: JSON.parse(decoder.decode(data)) });
    received.set(subscriptionId, list);
  });
  c.on('time', ({ timestamp }) => times.push(timestamp));
  c.on('status', (s) => statuses.push(s));
  c.on('parameterValues', (p) => parameterValues.push(p));
  return c;
}

async function subscribe(topic, count) {
  const id = client.subscribe(channels.get(topic).id);
  await until(`${count} messages on ${topic}`, () => (received.get(id)?.length ?? 0) >= count);
  return id;
}

before(async () => {
  server = await startServer(TOKEN);
  const printed = /^foxglove: (ws:\/\/\S+)$/m.exec(server.output.text);
  assert.ok(printed, `marsokhod run printed no "foxglove: ws://…" line; it said:\n${server.output.text}`);
  url = printed[1];
  client = connect(url);
});

after(async () => {
  client?.close();
  const result = await server?.stop();
  if (result) assert.equal(result.code, 0, `marsokhod run exited with ${JSON.stringify(result)}`);
});

test('the printed address carries the token, and the server advertises every channel with a JSON Schema', async () => {
  assert.equal(url, `ws://127.0.0.1:${server.port}/foxglove?token=${TOKEN}`);
  await until('every channel is advertised', () => TOPICS.every((t) => channels.has(t)));
  assert.deepEqual(serverInfo.capabilities, ['time', 'parameters', 'parametersSubscribe']);
  assert.deepEqual([...channels.keys()].sort(), TOPICS);
  for (const channel of channels.values()) {
    assert.equal(channel.encoding, 'json', channel.topic);
    assert.equal(channel.schemaEncoding, 'jsonschema', channel.topic);
    assert.equal(JSON.parse(channel.schema).type, 'object', channel.topic);
  }
  assert.equal(channels.get('/tf').schemaName, 'foxglove.FrameTransform');
  assert.equal(channels.get('/tf/links').schemaName, 'foxglove.FrameTransforms');
  assert.equal(channels.get('/pose').schemaName, 'foxglove.PoseInFrame');
  // Figure 8.1's status: per motor p, w, l, d, ŵ; U, Ū, D, κ, σ, the yaw rate, mode, gait, faults.
  const status = JSON.parse(channels.get('/status').schema).properties;
  for (const key of ['supply_v', 'reference_supply_v', 'max_duty', 'driving_scale', 'slope_rad',
    'yaw_rate_radps', 'mode', 'gait', 'faults', 'motors', 'settings']) {
    assert.ok(key in status, `the /status schema has ${key}`);
  }
  for (const key of ['position_rad', 'velocity_radps', 'load_radps', 'duty', 'commanded_radps']) {
    assert.ok(key in status.motors.properties.FL.properties, `the /status schema has motors.FL.${key}`);
  }
});

test('a subscription gets the status as its schema describes it, logged at the mission time, and the time advances', async () => {
  await until('every channel is advertised', () => TOPICS.every((t) => channels.has(t)));
  const id = await subscribe('/status', 10);
  const schema = JSON.parse(channels.get('/status').schema).properties;
  const messages = received.get(id);
  for (const { time, value } of messages) {
    for (const key of Object.keys(schema)) assert.ok(key in value, `status has ${key}`);
    assert.equal(Object.keys(value.motors).length, 8);
    assert.equal(time, BigInt(Math.round(value.mission_time_s * 1e9)), 'log time = mission time');
  }
  const missionTimes = messages.map((m) => m.value.mission_time_s);
  for (let k = 1; k < missionTimes.length; ++k) assert.ok(missionTimes[k] > missionTimes[k - 1], 'mission time advances');
  // Time messages: the server's clock is the mission time, and it advances too.
  await until('10 time messages', () => times.length >= 10);
  for (let k = 1; k < times.length; ++k) assert.ok(times[k] >= times[k - 1]);
  assert.ok(times.at(-1) > times[0]);
  assert.ok(times.at(-1) >= messages.at(-1).time);

  // Unsubscribed: the next ten time messages come without a status.
  client.unsubscribe(id);
  client.getParameters([], 'after-unsubscribe');
  await until('the server handled the unsubscribe', () => parameterValues.some((p) => p.id === 'after-unsubscribe'));
  const count = messages.length;
  const seen = times.length;
  await until('10 more time messages', () => times.length >= seen + 10);
  assert.equal(received.get(id).length, count, 'no status after unsubscribing');
});

test('the links are the URDF\'s, and the decoded CAN frames have the fields of `marsokhod decode --json`', async () => {
  await until('every channel is advertised', () => TOPICS.every((t) => channels.has(t)));
  const urdf = execFileSync(SERVER_BIN, ['urdf'], { cwd: REPO_DIR, encoding: 'utf8' });
  const links = [...urdf.matchAll(/<link name="([^"]+)">/g)].map((m) => m[1]).sort();
  const id = await subscribe('/tf/links', 2);
  const { value } = received.get(id).at(-1);
  const children = value.transforms.map((t) => t.child_frame_id);
  assert.deepEqual(['base_link', ...children].sort(), links);
  for (const t of value.transforms) {
    const q = t.rotation;
    assert.ok(Math.abs(Math.hypot(q.x, q.y, q.z, q.w) - 1) < 1e-9, `${t.child_frame_id}: a unit quaternion`);
  }

  const rawId = await subscribe('/can/raw', 20);
  const decodedId = await subscribe('/can/decoded', 20);
  client.unsubscribe(rawId);
  client.unsubscribe(decodedId);
  const decoded = received.get(decodedId).map((m) => m.value);
  const raw = received.get(rawId).map((m) => m.value).find((r) =>
    decoded.some((d) => d.timestamp === r.timestamp && d.id === r.id));
  assert.ok(raw, 'a frame seen on both channels');
  const line = `(${raw.timestamp}) can0 ${raw.id.toString(16).toUpperCase().padStart(3, '0')}#${raw.data}\n`;
  const cli = JSON.parse(execFileSync(SERVER_BIN, ['decode', '--json', '-'], { cwd: REPO_DIR, input: line, encoding: 'utf8' }));
  const live = decoded.find((d) => d.timestamp === raw.timestamp && d.id === raw.id);
  assert.deepEqual(Object.keys(live), Object.keys(cli), 'the same fields, in the same order');
  assert.equal(live.node, cli.node);
  assert.equal(live.type, cli.type);
});

test('the settings in force are parameters; setting them is refused to a client without control', async () => {
  client.getParameters([], 'all');
  await until('the parameters', () => parameterValues.some((p) => p.id === 'all'));
  const { parameters } = parameterValues.find((p) => p.id === 'all');
  const names = parameters.map((p) => p.name).sort();
  assert.deepEqual(names, ['behaviours.axle_placement', 'behaviours.contract_on_turn',
    'behaviours.power_management', 'behaviours.slant_response', 'load_distribution', 'max_drop_v',
    'speed_scale', 'supply']);
  const id = client.subscribe(channels.get('/status').id);
  await until('a status', () => (received.get(id)?.length ?? 0) >= 1);
  const settings = received.get(id).at(-1).value.settings;
  client.unsubscribe(id);
  const value = (name) => parameters.find((p) => p.name === name).value;
  assert.equal(value('speed_scale'), settings.speed_scale);
  assert.equal(value('max_drop_v'), settings.max_drop_v);
  assert.equal(value('load_distribution'), settings.load_distribution);
  assert.equal(value('behaviours.slant_response'), settings.behaviours.slant_response);

  const before = statuses.length;
  client.setParameters([{ name: 'speed_scale', value: 0.5 }], 'set');
  await until('the refusal', () => statuses.length > before);
  const refusal = statuses[before];
  assert.equal(refusal.level, 2);
  assert.match(refusal.message, /^setParameters: read-only: take control first/);
  assert.ok(!parameterValues.some((p) => p.id === 'set'), 'no values for a refused set');
});
