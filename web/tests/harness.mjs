// What the console's browser tests need around them: the real server (`marsokhod run`, simulator
// + driver + link in one process, real time) as a child process, Debian's chromium driven by
// playwright-core, a scripted standard-mapping gamepad, and bounded waits on the status.

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

export const WEB_DIR = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
export const REPO_DIR = path.resolve(WEB_DIR, '..');
export const DIST_DIR = path.join(WEB_DIR, 'dist');
export const SCREENSHOT_DIR = path.join(REPO_DIR, 'build', 'screenshots');
export const SERVER_BIN = process.env.MARSOKHOD_BIN ?? path.join(REPO_DIR, 'build', 'src', 'app', 'marsokhod');
const CHROMIUM = process.env.CHROMIUM_PATH ?? '/usr/bin/chromium';
const SERVER_START_TIMEOUT_MS = 15000;
const SERVER_EXIT_TIMEOUT_MS = 5000;

export const WHEELS = ['FL', 'FR', 'CL', 'CR', 'BL', 'BR'];

function freePort() {
  return new Promise((resolve, reject) => {
    const probe = net.createServer();
    probe.on('error', reject);
    probe.listen(0, '127.0.0.1', () => {
      const { port } = probe.address();
      probe.close(() => resolve(port));
    });
  });
}

export function checkPrerequisites() {
  if (!fs.existsSync(CHROMIUM)) {
    throw new Error(`chromium not found at ${CHROMIUM}: install it with scripts/install-deps.sh ` +
      '(apt-get install chromium), or point CHROMIUM_PATH at a Chromium binary');
  }
  if (!fs.existsSync(path.join(DIST_DIR, 'index.html'))) {
    throw new Error(`${DIST_DIR}/index.html is missing: build the console first (npm run build in web/)`);
  }
  if (!fs.existsSync(SERVER_BIN)) {
    throw new Error(`${SERVER_BIN} is missing: build marsokhod first (cmake --build build), ` +
      'or point MARSOKHOD_BIN at the binary');
  }
}

// Starts `marsokhod run` on a free port; resolves when it prints its console address.
// `extra`: more arguments for `marsokhod run` (e.g. --scenario FILE).
export async function startServer(token, extra = []) {
  const port = await freePort();
  // The token from the environment, as an operator should give it (argv is visible in ps).
  const args = ['run', '--listen', `127.0.0.1:${port}`, '--web', DIST_DIR, '--quiet', ...extra];
  const child = spawn(SERVER_BIN, args, {
    cwd: REPO_DIR, stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, MARSOKHOD_TOKEN: token },
  });
  const output = { text: '' };
  child.stdout.on('data', (d) => { output.text += d; });
  child.stderr.on('data', (d) => { output.text += d; });
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal })));
  const url = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(
      `marsokhod run printed no "console: …" line within ${SERVER_START_TIMEOUT_MS} ms; it said:\n${output.text}`)),
    SERVER_START_TIMEOUT_MS);
    const look = () => {
      const match = /^console: (http:\/\/\S+)$/m.exec(output.text);
      if (match) { clearTimeout(timer); resolve(match[1]); }
    };
    child.stdout.on('data', look);
    child.on('error', (err) => { clearTimeout(timer); reject(new Error(`cannot start ${SERVER_BIN}: ${err.message}`)); });
    exited.then(({ code, signal }) => {
      clearTimeout(timer);
      reject(new Error(`marsokhod run exited (code ${code}, signal ${signal}) before it served; it said:\n${output.text}`));
    });
  });
  return {
    url, port, output,
    // SIGTERM, then the exit status; SIGKILL if it does not end in time.
    async stop() {
      if (child.exitCode !== null || child.signalCode !== null) return exited;
      child.kill('SIGTERM');
      const timer = setTimeout(() => child.kill('SIGKILL'), SERVER_EXIT_TIMEOUT_MS);
      const result = await exited;
      clearTimeout(timer);
      return result;
    },
  };
}

export function launchBrowser() {
  // playwright-core gives each launch a fresh temporary profile (--user-data-dir) of its own.
  return chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
}

// A page in a context of its own (a console of its own), with a scripted standard-mapping
// gamepad: `setPad(page, {axes, buttons})` moves its sticks.
export async function openConsole(browser, url, { gamepad = false } = {}) {
  const context = await browser.newContext({ viewport: { width: 1400, height: 1000 } });
  if (gamepad) {
    await context.addInitScript(() => {
      const pad = {
        id: 'scripted test pad (STANDARD GAMEPAD)', index: 0, connected: true, mapping: 'standard',
        timestamp: 0, axes: [0, 0, 0, 0],
        buttons: Array.from({ length: 17 }, () => ({ pressed: false, touched: false, value: 0 })),
      };
      window.__testPad = pad;
      Object.defineProperty(Navigator.prototype, 'getGamepads', {
        configurable: true, value: () => [pad, null, null, null],
      });
    });
  }
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (err) => problems.push(`page error: ${err.message}`));
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
  page.problems = problems;
  await page.goto(url);
  return page;
}

export function setPad(page, { axes = [0, 0, 0, 0], buttons = [] } = {}) {
  return page.evaluate(([a, b]) => {
    window.__testPad.axes = a;
    window.__testPad.buttons.forEach((button, i) => {
      button.pressed = b.includes(i);
      button.value = button.pressed ? 1 : 0;
    });
    window.__testPad.timestamp = performance.now();
  }, [axes, buttons]);
}

export function latestStatus(page) {
  return page.evaluate(() => window.marsokhod.status);
}

// Waits until `predicate(status, arg)` holds for the page's newest status, polled every 20 ms
// from here (the console's Content-Security-Policy forbids eval in the page, rightly); the error
// names what was awaited and shows the newest status' relevant part.
export async function waitForStatus(page, what, predicate, arg, timeoutMs) {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    const status = await latestStatus(page);
    if (status != null && predicate(status, arg ?? null)) return;
    if (Date.now() >= deadline) break;
    await new Promise((resolve) => setTimeout(resolve, 20));
  }
  const s = await latestStatus(page).catch(() => null);
  const brief = s && {
    mission_time_s: s.mission_time_s, mode: s.mode, targets: s.targets, commands: s.commands,
    duty: WHEELS.map((w) => s.motors?.[w]?.duty), position_m: s.truth?.position_m,
    operator_timeout: s.operator_timeout, operator_rejection: s.operator_rejection, faults: s.faults,
    stop_latched: s.stop_latched, stop_reason: s.stop_reason,
  };
  throw new Error(`timed out after ${timeoutMs} ms waiting until ${what}; newest status: ` +
    `${JSON.stringify(brief)}`);
}

export async function waitForLinkState(page, state, timeoutMs) {
  try {
    await page.waitForFunction((s) => document.getElementById('link-state').dataset.state === s,
      state, { timeout: timeoutMs });
  } catch (err) {
    const shown = await page.evaluate(() => [document.getElementById('link-state').textContent,
      document.getElementById('link-error').textContent]);
    throw new Error(`the link did not reach "${state}" within ${timeoutMs} ms; it shows ` +
      `"${shown[0]}", error "${shown[1]}"`, { cause: err });
  }
}

// Takes control with the page's button. The take-over's stop holds until the console's input is
// neutral; with `rearm` (the pad centred) this also waits until the driver has re-armed after
// this very take-over: a status whose stop names this client's take-over and is no longer
// latched. (The newest status when the link says "in control" may still be one from before the
// take-over reached the driver, unlatched; a loaded machine showed that window.)
export async function takeControl(page, { rearm = true, timeoutMs = 3000 } = {}) {
  await page.click('#take-control');
  await waitForLinkState(page, 'in-control', timeoutMs);
  if (!rearm) return;
  const id = await page.evaluate(() => window.marsokhod.link.clientId);
  await waitForStatus(page, `the neutral input re-armed after client ${id}'s take-over`,
    (s, reason) => s.stop_latched === false && s.stop_reason.startsWith(reason),
    `client ${id} took control`, timeoutMs);
}

export async function screenshot(page, name) {
  fs.mkdirSync(SCREENSHOT_DIR, { recursive: true });
  const file = path.join(SCREENSHOT_DIR, name);
  await page.screenshot({ path: file, fullPage: true });
  return file;
}
