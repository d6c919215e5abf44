// The 3-D view's ruts on soft soil (issue #14), against the real server: `marsokhod run
// --scenario` with the terrain of the shipped sideways-drift-soft-sand (flat soft sand; `run`
// takes a scenario's terrain and faults, the operator drives). The status carries the soil's
// surface around the rover about once a second (status.truth.soil, docs/operator-protocol.md)
// and the view draws it.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import {
  checkPrerequisites, startServer, launchBrowser, openConsole, screenshot, REPO_DIR,
} from './harness.mjs';

const TOKEN = 'soil-test-token-0123456789abcdef';
const SCENARIO = path.join(REPO_DIR, 'scenarios', 'sideways-drift-soft-sand.toml');
const TIMEOUT_MS = 30000;
let server;
let browser;

before(async () => {
  checkPrerequisites();
  server = await startServer(TOKEN, ['--scenario', SCENARIO]);
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  if (server) await server.stop();
});

test('on soft sand the status carries the ruts and the 3-D view draws them', async () => {
  const page = await openConsole(browser, server.url);
  // The patch: 3.2 m × 2.0 m at every second 2-cm cell, 80 × 50 samples around the rover.
  await page.waitForFunction(() => document.getElementById('view3d')?.dataset.soil === '80x50',
    null, { timeout: TIMEOUT_MS });
  const patch = await page.waitForFunction(() => window.marsokhod.status?.truth?.soil,
    null, { timeout: TIMEOUT_MS, polling: 10 }).then((h) => h.jsonValue());
  const rover = (await page.evaluate(() => window.marsokhod.status.truth.position_m));
  assert.equal(patch.height_mm.length, 80 * 50);
  assert.equal(patch.cell_m, 0.04);
  // Centred on the rover to within a sampled cell.
  const centre = [patch.origin_m[0] + 79 * 0.02, patch.origin_m[1] + 49 * 0.02];
  assert.ok(Math.abs(centre[0] - rover[0]) <= 0.04 && Math.abs(centre[1] - rover[1]) <= 0.04,
    `the patch's centre ${centre} is not at the rover ${rover}`);
  // The standing wheels have pressed their ruts: the centre wheels under the centre unit's 30 kg
  // 1–3 cm (Bekker's static sinkage, docs/simulator.md).
  await page.waitForFunction(() => Number(document.getElementById('view3d')?.dataset.soilLowestMm) <= -10,
    null, { timeout: TIMEOUT_MS });
  await screenshot(page, 'console-soft-sand-ruts.png');
  assert.deepEqual(page.problems, []);
});
