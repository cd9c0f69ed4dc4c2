// End-to-end test of the web client's Metro view: imports the sample data into a fresh
// database, serves it with the built web client, and drives headless Chromium through the
// city picker, checking that every station (and, for Vienna, every POI) is drawn.
//
// Run from the repository root: node tests/e2e/metro_view.test.mjs
// Environment: TOURMAP_BIN (build/tourmap), TOURMAP_WEB_ROOT (build/web),
// TOURMAP_DATA_DIR (../shared/data), TOURMAP_MANIFEST (scripts/sample-data.json).

import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { createInterface } from 'node:readline';
import { fileURLToPath } from 'node:url';

const OVERALL_TIMEOUT_MS = 90_000;
const STEP_TIMEOUT_MS = 20_000;
const FIRST_CITY = 'vienna';
const SECOND_CITY = 'lisbon';

const repoRoot = fileURLToPath(new URL('../..', import.meta.url));
// Paths from the environment are taken as given (relative to the working directory);
// the defaults are relative to the repository root.
const setting = (name, fallback) => (process.env[name] ? resolve(process.env[name]) : resolve(repoRoot, fallback));
const bin = setting('TOURMAP_BIN', 'build/tourmap');
const webRoot = setting('TOURMAP_WEB_ROOT', 'build/web');
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

class TestFailure extends Error {}

function check(condition, message) {
  if (!condition) throw new TestFailure(message);
}

/** Starts `tourmap serve` and resolves with its base URL, read from the first stdout line. */
function startServer(db, serverLog) {
  const child = spawn(bin, ['serve', '--db', db, '--port', '0', '--web-root', webRoot, '--access-log', 'off'], {
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

async function apiJson(baseUrl, path) {
  const response = await fetch(baseUrl + path);
  check(response.ok, `GET ${path} answered ${response.status}`);
  return response.json();
}

/** Picks a city and waits until the map says it has drawn it; returns the drawn markers. */
async function pickCity(page, cityId) {
  await page.selectOption('[data-testid=city-picker]', cityId);
  await page.waitForSelector(`[data-testid=metro-map][data-status=ready][data-city="${cityId}"]`, {
    timeout: STEP_TIMEOUT_MS,
  });
  return {
    stations: await page.locator('circle.station').count(),
    pois: await page.locator('.poi').count(),
    hash: await page.evaluate(() => window.location.hash),
  };
}

async function run(state) {
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

  const server = startServer(db, state.serverLog);
  state.server = server.child;
  const baseUrl = await server.ready;

  const { cities } = await apiJson(baseUrl, '/api/v1/cities');
  const city = (id) => cities.find((candidate) => candidate.id === id);
  check(city(FIRST_CITY) && city(SECOND_CITY), `the API lists no ${FIRST_CITY} or no ${SECOND_CITY}`);
  const first = city(FIRST_CITY).counts;
  const second = city(SECOND_CITY).counts;
  check(first.stations > 0 && first.pois > 0, `${FIRST_CITY} has no stations or no POIs in the API`);
  check(second.stations > 0 && second.stations !== first.stations, `${SECOND_CITY} must have another station count`);

  state.context = await chromium.launchPersistentContext(join(state.tmp, 'profile'), {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 1280, height: 800 },
  });
  const page = state.context.pages()[0] ?? (await state.context.newPage());
  page.setDefaultTimeout(STEP_TIMEOUT_MS);
  page.on('console', (message) => {
    if (message.type() === 'error') state.consoleErrors.push(message.text());
  });
  page.on('pageerror', (error) => state.consoleErrors.push(`uncaught: ${error.message}`));

  const home = await page.goto(`${baseUrl}/`);
  check(home?.status() === 200, `GET / answered ${home?.status()}: is ${webRoot} the built web client?`);
  await page.waitForSelector('[data-testid=city-picker]:not([disabled])');
  const options = await page.locator('[data-testid=city-picker] option').count();
  check(options === cities.length, `the picker offers ${options} cities, the API lists ${cities.length}`);

  const drawnFirst = await pickCity(page, FIRST_CITY);
  check(
    drawnFirst.stations === first.stations,
    `${FIRST_CITY}: ${drawnFirst.stations} stations drawn, the API counts ${first.stations}`,
  );
  check(drawnFirst.pois === first.pois, `${FIRST_CITY}: ${drawnFirst.pois} POIs drawn, the API counts ${first.pois}`);
  check(drawnFirst.hash === `#/metro/${FIRST_CITY}`, `the route is ${drawnFirst.hash} after picking ${FIRST_CITY}`);
  const credits = await page.locator('.attribution').innerText();
  check(credits.includes('Wiener Linien'), `the attribution does not credit the data: "${credits}"`);
  state.summary.push(`${FIRST_CITY}: ${drawnFirst.stations} stations, ${drawnFirst.pois} POIs`);

  const drawnSecond = await pickCity(page, SECOND_CITY);
  check(
    drawnSecond.stations === second.stations,
    `${SECOND_CITY}: ${drawnSecond.stations} stations drawn, the API counts ${second.stations}`,
  );
  check(drawnSecond.pois === second.pois, `${SECOND_CITY}: ${drawnSecond.pois} POIs drawn, the API counts ${second.pois}`);
  state.summary.push(`${SECOND_CITY}: ${drawnSecond.stations} stations, ${drawnSecond.pois} POIs`);

  // A reload keeps the view and the city (hash routing).
  await page.reload();
  await page.waitForSelector(`[data-testid=metro-map][data-status=ready][data-city="${SECOND_CITY}"]`);
  const picked = await page.locator('[data-testid=city-picker]').inputValue();
  check(picked === SECOND_CITY, `after a reload the picker shows ${picked}, not ${SECOND_CITY}`);
  state.summary.push('reload keeps the city');

  check(state.consoleErrors.length === 0, `the page logged errors:\n  ${state.consoleErrors.join('\n  ')}`);
}

async function cleanUp(state) {
  await state.context?.close().catch(() => {});
  if (state.server) await stopServer(state.server);
  if (state.tmp) rmSync(state.tmp, { recursive: true, force: true });
}

const state = { serverLog: [], consoleErrors: [], summary: [] };
const started = Date.now();
let failure;
const deadline = setTimeout(() => {
  console.error(`FAIL metro_view: no result after ${OVERALL_TIMEOUT_MS / 1000} s`);
  // Best effort, then out: whatever hangs must not keep the test alive.
  state.server?.kill('SIGKILL');
  if (state.tmp) rmSync(state.tmp, { recursive: true, force: true });
  process.exit(1);
}, OVERALL_TIMEOUT_MS);

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
  console.error(`FAIL metro_view (${seconds} s): ${failure instanceof TestFailure ? failure.message : failure.stack}`);
  if (state.serverLog.length > 0) console.error(`server output:\n${state.serverLog.join('').trimEnd()}`);
  console.log('0 passed, 1 failed');
  process.exit(1);
}
console.log(`PASS metro_view (${seconds} s): ${state.summary.join('; ')}; no console errors`);
console.log('1 passed, 0 failed');
