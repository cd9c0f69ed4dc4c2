// Browser benchmark of the Deform view while a focus region is dragged (issue 15): Debian's
// chromium drives the built client against a real server with the sample data, drags the
// region's centre round a circle for a few seconds on each network, and prints a table of map
// updates per second (deformed maps received and drawn), browser frames per second and their
// p95 interval, the median round trip, and the last answer's decode and draw times, for the
// positions as JSON (the baseline, the answer a client gets without asking for binary) and as
// binary (api/positions_binary.hpp), measured in the same run; and binary without the context
// layers (sea, water, land use, buildings, rivers, names: GET /roads/{id}/context refused), the
// baseline of what drawing and warping them costs.
//
// Run from the repository root after ./scripts/build:
//   node bench/deform_drag_bench.mjs [--seconds 5] [--networks monaco,liechtenstein]
// Environment as the browser tests: TOURMAP_BIN, TOURMAP_WEB_ROOT, TOURMAP_DATA_DIR, TOURMAP_MANIFEST.

import { check, openApp, openPage, runTest, serveSampleData } from '../tests/e2e/support.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
};
const SECONDS = Number(option('seconds', '5'));
const NETWORKS = option('networks', 'monaco,liechtenstein').split(',');
const CANVAS = '[data-testid=road-canvas]';
const STATS = '[data-testid=deform-stats]';
const RADIUS_PX = 60;
const STEP_MS = 16;  // one pointer move per 60 Hz frame, as a hand on a mouse

/** Drags the focus handle round a circle for SECONDS; returns what the page measured. */
async function drag(page) {
  // The overlay is drawn again with each answer (the handle moves towards the click while the
  // first answers come): wait for the answers to stop, and take the handle's box again if it
  // was redrawn in between.
  await page.waitForFunction((selector) => document.querySelector(selector)?.dataset.busy === 'false', CANVAS, { timeout: 30_000 });
  let handle = null;
  for (let attempt = 0; attempt < 10 && !handle; attempt++) handle = await page.locator('.focus-handle').first().boundingBox();
  check(handle, 'no focus region handle on the map');
  const cx = handle.x + handle.width / 2, cy = handle.y + handle.height / 2;
  await page.evaluate(() => {
    // Frame intervals while the drag lasts, from requestAnimationFrame.
    window.__frames = [];
    window.__recording = true;
    const tick = (t) => {
      window.__frames.push(t);
      if (window.__recording) requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  const started = Date.now();
  let moves = 0;
  for (let due = started; Date.now() - started < SECONDS * 1000; due += STEP_MS) {
    const angle = ((Date.now() - started) / 1000) * Math.PI;  // half a turn per second
    await page.mouse.move(cx + RADIUS_PX * Math.sin(angle), cy + (RADIUS_PX * (1 - Math.cos(angle))) / 2);
    moves++;
    const wait = due + STEP_MS - Date.now();
    if (wait > 0) await page.waitForTimeout(wait);
  }
  const movesPerSecond = moves / ((Date.now() - started) / 1000);
  await page.mouse.up();
  const frames = await page.evaluate(() => {
    window.__recording = false;
    return window.__frames;
  });
  const intervals = frames.slice(1).map((t, i) => t - frames[i]).sort((a, b) => a - b);
  const p95 = intervals.length ? intervals[Math.min(intervals.length - 1, Math.floor(0.95 * intervals.length))] : NaN;
  const stats = await page.locator(STATS).evaluate((element) => ({ ...element.dataset }));
  const canvas = await page.locator(CANVAS).evaluate((element) => ({ ...element.dataset }));
  return {
    movesPerSecond,
    updatesPerSecond: Number(stats.dragUpdatesPerSecond),
    answers: Number(stats.dragUpdates),
    fps: Number(stats.dragFps),
    p95FrameMs: p95,
    rttMs: Number(stats.dragRttMedian),
    applyMs: Number(canvas.applyMs),
    contextVertices: Number(canvas.contextVertices || 0),
    drawMs: Number(canvas.drawMs),
    errors: Number(canvas.errors || 0),
  };
}

async function measure(page, baseUrl, network, wire, context = true) {
  await page.unroute('**/api/v1/deform/**').catch(() => {});
  await page.unroute('**/api/v1/roads/*/context*').catch(() => {});
  if (!context) await page.route('**/api/v1/roads/*/context*', (route) => route.abort());
  // The JSON baseline: the request without the client's Accept, as an older client sends it.
  // Only there: an intercepted request makes a round trip through this process (~20-50 ms on
  // two busy cores), which is no part of what a user waits for.
  if (wire === 'json')
    await page.route('**/api/v1/deform/**', (route) =>
      route.continue({ headers: { ...route.request().headers(), accept: 'application/json' } }));
  await page.goto('about:blank');  // a fresh load of the client for each row
  await openApp(page, baseUrl, `#/deform/${network}`);
  await page.waitForSelector(`${CANVAS}[data-status=ready][data-network="${network}"]`, { timeout: 60_000 });
  if (context) await page.waitForSelector(`${CANVAS}[data-context-vertices]`, { timeout: 60_000 });
  const map = await page.locator('[data-testid=road-map]').boundingBox();
  await page.mouse.click(map.x + map.width / 2, map.y + map.height / 2);
  await page.waitForFunction((selector) => Number(document.querySelector(selector)?.dataset.requests) >= 1, CANVAS, { timeout: 60_000 });
  return drag(page);
}

async function run(state) {
  const baseUrl = await serveSampleData(state);
  const page = await openPage(state);
  const rows = [];
  for (const network of NETWORKS) {
    const json = await measure(page, baseUrl, network, 'json');
    const bare = await measure(page, baseUrl, network, 'binary', false);
    const binary = await measure(page, baseUrl, network, 'binary');
    for (const [wire, r] of [['JSON', json], ['binary, no context', bare], ['binary', binary]])
      rows.push(`| ${network} | ${wire} | ${r.contextVertices} | ${r.movesPerSecond.toFixed(0)} | ${r.updatesPerSecond.toFixed(1)} | ${(r.updatesPerSecond / json.updatesPerSecond).toFixed(2)}x | ${r.answers} | ${r.fps.toFixed(1)} | ${r.p95FrameMs.toFixed(1)} | ${r.rttMs.toFixed(1)} | ${r.applyMs.toFixed(1)} | ${r.drawMs.toFixed(1)} | ${r.errors} |`);
  }
  console.log(`\n# Deform view while dragging a focus region (${SECONDS} s per row, 1280 x 800, chromium headless)\n`);
  console.log('pointer moves/s: what the benchmark sent (one per 16 ms at most); updates/s: deformed maps received and drawn per second of drag (vs JSON in the same run); fps and p95: browser frames and their interval; round trip: median, request to parsed answer; decode+project, with the warp of the context layers, and draw: the last answer\'s, ms.\n');
  console.log('| network | positions | context vertices | pointer moves/s | updates/s | vs JSON | answers | fps | p95 frame ms | round trip ms | decode+project ms | draw ms | errors |');
  console.log('|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|');
  for (const row of rows) console.log(row);
  console.log('');
  state.summary.push(`${rows.length} rows`);
}

await runTest('deform_drag_bench', 60_000 + NETWORKS.length * 3 * (SECONDS * 1000 + 60_000), run);
