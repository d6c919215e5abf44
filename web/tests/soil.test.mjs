// The 3-D view's ruts on soft soil (issue #14), against the real server: `marsokhod run
// --scenario` with the terrain of the shipped sideways-drift-soft-sand (flat soft sand; `run`
// takes a scenario's terrain and faults, the operator drives). The status carries the soil's
// surface around the rover about once a second (status.truth.soil, docs/operator-protocol.md)
// and the view draws it.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import {
  checkPrerequisites, startServer, launchBrowser, openConsole, screenshot, takeControl,
  REPO_DIR,
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
  // Drive forward 6 s (W): the wheels leave their ruts behind them, 1–3 cm deep (Bekker's
  // sinkage under a sixth of the rover, docs/simulator.md), in the camera's view behind the rover.
  await page.waitForFunction(() => window.marsokhod.status?.mode === 'driving', null,
    { timeout: TIMEOUT_MS });  // the driver's start-up done
  await takeControl(page);
  await page.locator('body').click({ position: { x: 5, y: 300 } });  // the keyboard's focus on the page
  await page.keyboard.down('KeyW');
  await page.waitForFunction(() => window.marsokhod.status?.targets?.v1_radps > 1, null,
    { timeout: 3000 });  // W reached the driver
  await page.waitForTimeout(6000);
  await page.keyboard.up('KeyW');
  const driven = await page.evaluate(([x, y]) => {
    const p = window.marsokhod.status.truth.position_m;
    return Math.hypot(p[0] - x, p[1] - y);
  }, rover);
  assert.ok(driven > 0.1, `the rover drove only ${driven} m`);
  // Two more patches (about 2 s): the last one sent after the rover stopped.
  const patches = await page.evaluate(() => Number(document.getElementById('view3d').dataset.soilPatches));
  await page.waitForFunction((n) => Number(document.getElementById('view3d').dataset.soilPatches) >= n + 2,
    patches, { timeout: TIMEOUT_MS });
  assert.ok(await page.evaluate(() => Number(document.getElementById('view3d').dataset.soilDeepestMm) <= -10),
    'no rut 1 cm deep in the patch');
  // The ruts are drawn, not hidden under the ground plane: rendered with the soil and without it,
  // the picture has pixels where the soil is clearly darker than the ground it covers (a rut:
  // 1 cm deep is 0.85 of the sand's brightness, 3 cm 0.55).
  const darker = await page.evaluate(() => {
    const view = window.marsokhod.view;
    const read = () => {
      view.dirty = true;
      view.draw();
      const canvas = view.stage.renderer.domElement;
      const copy = document.createElement('canvas');
      copy.width = canvas.width;
      copy.height = canvas.height;
      const g = copy.getContext('2d');
      g.drawImage(canvas, 0, 0);
      return g.getImageData(0, 0, copy.width, copy.height).data;
    };
    const withSoil = read();
    view.soil.visible = false;
    const without = read();
    view.soil.visible = true;
    view.dirty = true;
    let count = 0;
    for (let i = 0; i < withSoil.length; i += 4) {
      const a = withSoil[i] + withSoil[i + 1] + withSoil[i + 2];
      const b = without[i] + without[i + 1] + without[i + 2];
      if (a < b - 60) ++count;
    }
    return count;
  });
  assert.ok(darker >= 200, `only ${darker} pixels show a rut darker than the ground`);
  await screenshot(page, 'console-soft-sand-ruts.png');
  assert.deepEqual(page.problems, []);
  // A reconnect takes the old ruts away (the server could now run on rigid ground), and the next
  // patch brings them back: the view's soil goes 'none', then 80x50 again.
  await page.evaluate(() => {
    const container = document.getElementById('view3d');
    window.soilShown = [];
    new MutationObserver(() => window.soilShown.push(container.dataset.soil))
      .observe(container, { attributes: true, attributeFilter: ['data-soil'] });
    window.marsokhod.link.socket.close();
  });
  await page.waitForFunction(() => {
    const shown = window.soilShown;
    const cleared = shown.indexOf('none');
    return cleared >= 0 && shown.indexOf('80x50', cleared) > cleared;
  }, null, { timeout: TIMEOUT_MS });
  assert.equal(await page.evaluate(() => window.marsokhod.view.soil.visible), true);
});
