// recording.mcap as a tool nobody here wrote reads it: npm's @mcap/core (the MCAP reader Foxglove
// uses) on a recording made by the real binary (`marsokhod scenario FILE --out DIR`): the summary,
// the channels and their schemas, message counts against can.log, operator.jsonl and
// telemetry.csv, a few values, the configuration attached; then `marsokhod export-mcap` of the
// same folder.
//   MARSOKHOD_BIN=…   to use another binary

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { McapIndexedReader, McapStreamReader } from '@mcap/core';
import { REPO_DIR } from './harness.mjs';

const BIN = process.env.MARSOKHOD_BIN ?? path.join(REPO_DIR, 'build', 'src', 'app', 'marsokhod');
const CONFIG = path.join(REPO_DIR, 'config', 'marsokhod.toml');
const SCENARIO = `
duration_s = 4.0
[[input]]
t = 0.0
targets = { v1 = 0.0 }
[[input]]
t = 2.5
targets = { v1 = 1.5, v2 = 0.3 }
`;
const TOPICS = ['/can/decoded', '/can/raw', '/imu', '/joint_states', '/operator/input',
  '/operator/runtime', '/pose', '/pose/estimate', '/status', '/tf', '/tf/links'];

let dir;
let run;

function fileReadable(file) {
  const fd = fs.openSync(file, 'r');
  return {
    fd,
    size: async () => BigInt(fs.fstatSync(fd).size),
    read: async (offset, size) => {
      const buffer = new Uint8Array(Number(size));
      fs.readSync(fd, buffer, 0, Number(size), Number(offset));
      return buffer;
    },
  };
}

async function openIndexed(file) {
  const readable = fileReadable(file);
  const reader = await McapIndexedReader.Initialize({ readable });
  return { reader, close: () => fs.closeSync(readable.fd) };
}

async function messagesByTopic(reader) {
  const topicOf = new Map([...reader.channelsById].map(([id, c]) => [id, c.topic]));
  const out = new Map();
  const decoder = new TextDecoder();
  for await (const m of reader.readMessages()) {
    const topic = topicOf.get(m.channelId);
    if (!out.has(topic)) out.set(topic, []);
    out.get(topic).push({ logTime: m.logTime, value: JSON.parse(decoder.decode(m.data)) });
  }
  return out;
}

const lines = (file) => fs.readFileSync(file, 'utf8').split('\n').filter((l) => l.length > 0);

function telemetry(file) {
  const [header, ...rows] = lines(file);
  const names = header.split(',');
  return rows.map((r) => {
    const cells = r.split(',');
    return Object.fromEntries(names.map((n, i) => [n, Number(cells[i])]));
  });
}

before(() => {
  if (!fs.existsSync(BIN)) {
    throw new Error(`${BIN} is missing: build marsokhod first (cmake --build build), or point MARSOKHOD_BIN at it`);
  }
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'marsokhod-mcap-'));
  const scenario = path.join(dir, 'short.toml');
  fs.writeFileSync(scenario, SCENARIO);
  run = path.join(dir, 'run');
  execFileSync(BIN, ['--config', CONFIG, 'scenario', scenario, '--seed', '3', '--out', run, '--no-plots'],
    { stdio: 'pipe' });
});

after(() => {
  if (dir) fs.rmSync(dir, { recursive: true, force: true });
});

test('@mcap/core reads the summary, channels and schemas of a recording', async () => {
  const { reader, close } = await openIndexed(path.join(run, 'recording.mcap'));
  try {
    assert.equal(reader.header.library, 'marsokhod');
    const topics = [...reader.channelsById.values()].map((c) => c.topic).sort();
    assert.deepEqual(topics, TOPICS);
    for (const channel of reader.channelsById.values()) {
      assert.equal(channel.messageEncoding, 'json', channel.topic);
      const schema = reader.schemasById.get(channel.schemaId);
      assert.equal(schema.encoding, 'jsonschema', channel.topic);
      const parsed = JSON.parse(new TextDecoder().decode(schema.data));
      assert.equal(parsed.type, 'object', channel.topic);
    }
    const schemaOf = (topic) => {
      const channel = [...reader.channelsById.values()].find((c) => c.topic === topic);
      return reader.schemasById.get(channel.schemaId).name;
    };
    assert.equal(schemaOf('/tf'), 'foxglove.FrameTransform');
    assert.equal(schemaOf('/tf/links'), 'foxglove.FrameTransforms');
    assert.equal(schemaOf('/pose'), 'foxglove.PoseInFrame');

    const stats = reader.statistics;
    const cycles = lines(path.join(run, 'operator.jsonl')).length;
    const frames = lines(path.join(run, 'can.log')).length;
    const countOf = (topic) => {
      const channel = [...reader.channelsById.values()].find((c) => c.topic === topic);
      return Number(stats.channelMessageCounts.get(channel.id));
    };
    assert.equal(cycles, Math.ceil(4.0 / 0.0156));
    assert.equal(countOf('/status'), cycles);
    assert.equal(countOf('/tf'), cycles);
    assert.equal(countOf('/tf/links'), cycles);
    assert.equal(countOf('/can/raw'), frames);
    assert.equal(countOf('/can/decoded'), frames);
    const inputs = lines(path.join(run, 'operator.jsonl')).filter((l) => JSON.parse(l).input !== null).length;
    assert.equal(countOf('/operator/input'), inputs);
    assert.ok(reader.chunkIndexes.length > 1);
    assert.equal(stats.messageStartTime, 0n);

    // The configuration goes along.
    const attachments = [];
    for await (const a of reader.readAttachments()) attachments.push(a);
    assert.deepEqual(attachments.map((a) => a.name), ['config.toml']);
    assert.equal(new TextDecoder().decode(attachments[0].data), fs.readFileSync(path.join(run, 'config.toml'), 'utf8'));
    const metadata = [];
    for await (const m of reader.readMetadata()) metadata.push(m);
    assert.equal(metadata[0].name, 'marsokhod');
    assert.match(metadata[0].metadata.get('source'), /^scenario .* --seed 3$/);
  } finally {
    close();
  }
});

test('the messages agree with telemetry.csv and can.log', async () => {
  const { reader, close } = await openIndexed(path.join(run, 'recording.mcap'));
  let topics;
  try {
    topics = await messagesByTopic(reader);
  } finally {
    close();
  }
  const rows = telemetry(path.join(run, 'telemetry.csv'));
  const status = topics.get('/status');
  assert.equal(status.length, rows.length);
  for (const k of [0, 100, rows.length - 1]) {
    const s = status[k].value;
    const row = rows[k];
    assert.equal(status[k].logTime, BigInt(Math.round(row.t_s * 1e6)) * 1000n, `log time of cycle ${k}`);
    assert.ok(Math.abs(s.mission_time_s - row.t_s) < 1e-9);
    assert.ok(Math.abs(s.supply_v - row.supply_v) < 1e-6, `supply_v ${s.supply_v} ${row.supply_v}`);
    assert.ok(Math.abs(s.motors.CL.duty - row.CL_duty) < 1e-6);
    const joints = topics.get('/joint_states')[k].value;
    assert.equal(joints.name[7], 'joint_AR');
    assert.ok(Math.abs(joints.position[7] - row.AR_p_rad) < 1e-6);
    const tf = topics.get('/tf')[k].value;
    assert.ok(Math.abs(tf.translation.x - row.true_x_m) < 1e-6);
    const pose = topics.get('/pose/estimate')[k].value;
    assert.ok(Math.abs(pose.x_m - row.odo_x_m) < 1e-6);
    const imu = topics.get('/imu')[k].value;
    assert.ok(Math.abs(imu.yaw_rate_radps - row.yaw_rate_radps) < 1e-6);
  }
  // The rover drove: the true and the estimated pose moved forward.
  assert.ok(topics.get('/tf').at(-1).value.translation.x > 0.05);
  // Every frame of can.log, in order, raw and decoded.
  const can = lines(path.join(run, 'can.log'));
  const raw = topics.get('/can/raw');
  const decoded = topics.get('/can/decoded');
  for (const i of [0, 7, Math.floor(can.length / 2), can.length - 1]) {
    const stamp = can[i].slice(1, can[i].indexOf(')'));
    assert.equal(raw[i].value.timestamp, stamp);
    assert.ok(can[i].endsWith(`#${raw[i].value.data}`), `${can[i]} vs ${raw[i].value.data}`);
    assert.equal(decoded[i].value.timestamp, stamp);
    assert.equal(decoded[i].value.id, raw[i].value.id);
  }
  assert.ok(decoded.some((m) => m.value.type === 'control_response' && 'w_radps' in m.value));
});

test('every plotted path of docs/foxglove-layout.json is a number in the recording', async () => {
  const layout = JSON.parse(fs.readFileSync(path.join(REPO_DIR, 'docs', 'foxglove-layout.json'), 'utf8'));
  const { reader, close } = await openIndexed(path.join(run, 'recording.mcap'));
  let topics;
  try {
    topics = await messagesByTopic(reader);
  } finally {
    close();
  }
  const plots = Object.entries(layout.configById).filter(([id]) => id.startsWith('Plot!'));
  assert.equal(plots.length, 3);
  for (const [id, config] of plots) {
    for (const { value } of config.paths) {
      const [, topic, rest] = value.match(/^(\/[a-z/]+)\.(.*)$/);
      let v = topics.get(topic).at(-1).value;
      for (const part of rest.split('.')) {
        const [, key, index] = part.match(/^([a-z0-9_A-Z]+)(?:\[(\d+)\])?$/);
        v = v[key];
        if (index !== undefined) v = v[Number(index)];
      }
      assert.equal(typeof v, 'number', `${id}: ${value}`);
    }
  }
  assert.equal(layout.configById['RawMessages!status'].topicPath, '/status');
  assert.ok(topics.has(layout.configById['3D!view'].followTf === 'base_link' ? '/tf' : ''));
});

test('the stream reader reads the same messages in order', async () => {
  const reader = new McapStreamReader();
  reader.append(fs.readFileSync(path.join(run, 'recording.mcap')));
  let messages = 0;
  let footer = false;
  for (let record; (record = reader.nextRecord());) {
    if (record.type === 'Message') messages += 1;
    if (record.type === 'Footer') footer = true;
  }
  assert.ok(footer);
  assert.ok(reader.done());
  const { reader: indexed, close } = await openIndexed(path.join(run, 'recording.mcap'));
  close();
  assert.equal(BigInt(messages), indexed.statistics.messageCount);
});

test('export-mcap rebuilds recording.mcap from the folder', async () => {
  const live = path.join(dir, 'live.mcap');
  fs.renameSync(path.join(run, 'recording.mcap'), live);
  const out = execFileSync(BIN, ['--config', CONFIG, 'export-mcap', run], { encoding: 'utf8' });
  assert.match(out, /cycles, \d+ messages, \/tf from telemetry.csv/);
  const a = await openIndexed(live);
  const b = await openIndexed(path.join(run, 'recording.mcap'));
  try {
    const [ta, tb] = [await messagesByTopic(a.reader), await messagesByTopic(b.reader)];
    // Everything but /tf/links (telemetry.csv keeps no strut or tilt angles).
    assert.equal(tb.has('/tf/links'), false);
    assert.equal(b.reader.statistics.messageCount,
      a.reader.statistics.messageCount - BigInt(ta.get('/tf/links').length));
    assert.deepEqual(tb.get('/joint_states'), ta.get('/joint_states'));
    assert.deepEqual(tb.get('/can/decoded'), ta.get('/can/decoded'));
  } finally {
    a.close();
    b.close();
  }
  // Without can.log there is nothing to export.
  const empty = fs.mkdtempSync(path.join(dir, 'empty-'));
  assert.throws(() => execFileSync(BIN, ['--config', CONFIG, 'export-mcap', empty], { stdio: 'pipe' }),
    (e) => e.status === 2 && /has no can.log: not a recording/.test(e.stderr.toString()));
});
