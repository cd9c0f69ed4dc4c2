// Shared parts of the browser tests: settings from the environment, a fresh database with the
// sample data, the server, headless Chromium, and the PASS/FAIL protocol ctest reads.
//
// Environment: TOURMAP_BIN (build/tourmap), TOURMAP_WEB_ROOT (build/web),
// TOURMAP_DATA_DIR (../shared/data), TOURMAP_MANIFEST (scripts/sample-data.json).

import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { createInterface } from 'node:readline';
import { fileURLToPath } from 'node:url';

const repoRoot = fileURLToPath(new URL('../..', import.meta.url));
// Paths from the environment are taken as given (relative to the working directory);
// the defaults are relative to the repository root.
const setting = (name, fallback) => (process.env[name] ? resolve(process.env[name]) : resolve(repoRoot, fallback));
export const bin = setting('TOURMAP_BIN', 'build/tourmap');
export const webRoot = setting('TOURMAP_WEB_ROOT', 'build/web');
const dataDir = setting('TOURMAP_DATA_DIR', '../shared/data');
const manifest = setting('TOURMAP_MANIFEST', 'scripts/sample-data.json');

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { chromium } = require('playwright-core');

const CHROMIUM_ARGS = [
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

export const STEP_TIMEOUT_MS = 20_000;

/** What requests to other hosts get (see openPage). */
const STAND_IN_PHOTO =
  '<svg xmlns="http://www.w3.org/2000/svg" width="40" height="40"><rect width="40" height="40" fill="#9ab"/></svg>';
const LOCAL_HOSTS = new Set(['127.0.0.1', 'localhost', '[::1]']);

export class TestFailure extends Error {}

export function check(condition, message) {
  if (!condition) throw new TestFailure(message);
}

/** Starts `tourmap serve` (with `extraArgs`) and resolves with its base URL, read from the first stdout line. */
function startServer(db, serverLog, extraArgs = []) {
  const args = ['serve', '--db', db, '--port', '0', '--web-root', webRoot, '--access-log', 'off', ...extraArgs];
  const child = spawn(bin, args, {
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  child.stderr.on('data', (chunk) => serverLog.push(String(chunk)));
  const ready = new Promise((resolveUrl, reject) => {
    const lines = createInterface({ input: child.stdout });
    lines.once('line', (line) => {
      serverLog.push(`${line}\n`);
      const match = /listening on (http:\/\/[^\s]+)/.exec(line);
      if (match) resolveUrl(match[1].replace(/\/$/, ''));
      else reject(new TestFailure(`unexpected first line from the server: ${line}`));
      lines.on('line', (more) => serverLog.push(`${more}\n`));
    });
    child.once('error', (error) => reject(new TestFailure(`cannot start ${bin}: ${error.message}`)));
    child.once('exit', (code) => reject(new TestFailure(`the server exited with code ${code} before listening`)));
  });
  return { child, ready };
}

async function stopServer(child) {
  if (child.exitCode !== null || child.signalCode !== null) return;
  const exited = new Promise((done) => child.once('exit', done));
  child.kill('SIGTERM');
  const timer = setTimeout(() => child.kill('SIGKILL'), 5000);
  await exited;
  clearTimeout(timer);
}

/**
 * Imports the sample data into a fresh database and serves it (with `serveArgs` added to
 * `tourmap serve`); resolves with the base URL.
 */
export async function serveSampleData(state, { serveArgs = [] } = {}) {
  state.tmp = mkdtempSync(join(tmpdir(), 'tourmap-e2e-'));
  const db = join(state.tmp, 't.db');
  const imported = spawnSync(bin, ['import', 'manifest', manifest, '--data-dir', dataDir, '--db', db], {
    encoding: 'utf8',
    timeout: 60_000,
  });
  check(
    imported.status === 0,
    `import failed (exit ${imported.status ?? imported.signal}): ${imported.error?.message ?? imported.stderr}`,
  );
  const server = startServer(db, state.serverLog, serveArgs);
  state.server = server.child;
  return server.ready;
}

export async function apiJson(baseUrl, path) {
  const response = await fetch(baseUrl + path);
  check(response.ok, `GET ${path} answered ${response.status}`);
  return response.json();
}

/**
 * Headless Chromium with one page; console errors and uncaught exceptions go to state.consoleErrors.
 * Requests to other hosts than the test server (POI photos on the data publishers' sites) are
 * answered with a small local picture: the tests must not depend on the internet, and a photo
 * that cannot be loaded would log a console error.
 */
export async function openPage(state) {
  state.context = await chromium.launchPersistentContext(join(state.tmp, 'profile'), {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 1280, height: 800 },
  });
  const page = state.context.pages()[0] ?? (await state.context.newPage());
  page.setDefaultTimeout(STEP_TIMEOUT_MS);
  await page.route(
    (url) => !LOCAL_HOSTS.has(url.hostname),
    (route) => route.fulfill({ status: 200, contentType: 'image/svg+xml', body: STAND_IN_PHOTO }),
  );
  page.on('console', (message) => {
    if (message.type() === 'error') state.consoleErrors.push(message.text());
  });
  page.on('pageerror', (error) => state.consoleErrors.push(`uncaught: ${error.message}`));
  return page;
}

/** Opens the app's start page and checks that the server serves the built client. */
export async function openApp(page, baseUrl, hash = '') {
  const home = await page.goto(`${baseUrl}/${hash}`);
  check(home?.status() === 200, `GET / answered ${home?.status()}: is ${webRoot} the built web client?`);
}

export function checkNoConsoleErrors(state) {
  check(state.consoleErrors.length === 0, `the page logged errors:\n  ${state.consoleErrors.join('\n  ')}`);
}

async function cleanUp(state) {
  await state.context?.close().catch(() => {});
  if (state.server) await stopServer(state.server);
  if (state.tmp) rmSync(state.tmp, { recursive: true, force: true });
}

/**
 * Runs one test: `run(state)` throws a TestFailure (or anything) to fail. Prints PASS or FAIL
 * (with the server's output) and the "N passed, M failed" line, and exits with 0 or 1.
 * state.summary collects what passed, for the PASS line.
 */
export async function runTest(name, overallTimeoutMs, run) {
  const state = { serverLog: [], consoleErrors: [], summary: [] };
  const started = Date.now();
  let failure;
  const deadline = setTimeout(() => {
    console.error(`FAIL ${name}: no result after ${overallTimeoutMs / 1000} s`);
    // Best effort, then out: whatever hangs must not keep the test alive.
    state.server?.kill('SIGKILL');
    if (state.tmp) rmSync(state.tmp, { recursive: true, force: true });
    process.exit(1);
  }, overallTimeoutMs);

  try {
    await run(state);
  } catch (error) {
    failure = error;
  } finally {
    await cleanUp(state);
    clearTimeout(deadline);
  }

  const seconds = ((Date.now() - started) / 1000).toFixed(1);
  if (failure) {
    console.error(`FAIL ${name} (${seconds} s): ${failure instanceof TestFailure ? failure.message : failure.stack}`);
    if (state.serverLog.length > 0) console.error(`server output:\n${state.serverLog.join('').trimEnd()}`);
    console.log('0 passed, 1 failed');
    process.exit(1);
  }
  console.log(`PASS ${name} (${seconds} s): ${state.summary.join('; ')}; no console errors`);
  console.log('1 passed, 0 failed');
}
