// End-to-end test of the web client's resilience: busy answers, lost WebSockets, plain words.
//
// 1. The first API requests are answered 429 (Retry-After: 1) and one 503 (Retry-After as an
//    HTTP date), intercepted in the browser: the Metro view still loads, the quiet
//    "Busy, retrying…" note was shown meanwhile and is gone after, and no status code or
//    status text appears on the page.
// 2. The events WebSocket (/api/v1/events) is closed under the page: the header says offline,
//    then live again on a second socket.
// 3. A request that stays busy beyond the client's retry budget ends in an error box in plain
//    words ("busy"), the HTTP status only in its collapsed Details.
// 4. The crowd stream's WebSocket is closed under the Crowd view: it reconnects on a new socket
//    and frames are drawn again.
//
// Run from the repository root: node tests/e2e/resilience.test.mjs
// Environment: TOURMAP_BIN (build/tourmap), TOURMAP_WEB_ROOT (build/web),
// TOURMAP_DATA_DIR (../shared/data), TOURMAP_MANIFEST (scripts/sample-data.json).
// TOURMAP_SCREENSHOTS: a directory to save screenshots of the busy note and the busy error in (optional).

import { join } from 'node:path';
import { check, checkNoConsoleErrors, openApp, openPage, runTest, serveSampleData } from './support.mjs';

const OVERALL_TIMEOUT_MS = 290_000;
/** The first crowd frame waits for the scene to be built on the server (software GL). */
const FIRST_FRAME_TIMEOUT_MS = 120_000;
const LOAD_TIMEOUT_MS = 60_000;
/** Answered 429 before the API is let through, then one 503. */
const BUSY_429 = 3;
/** What must never be on the page: status codes, status texts, the API's error codes or JSON. */
const RAW = /\b(429|503)\b|Too Many Requests|Service Unavailable|rate_limited|HTTP \d{3}|\{"error"/;

const busyBody = (status) =>
  JSON.stringify({ error: { code: status === 429 ? 'rate_limited' : 'busy', message: `test: ${status}` } });

/** The text a person sees in the page's boxes and notes (closed <details> are not rendered, so not in innerText). */
async function visibleMessages(page) {
  return page.evaluate(() =>
    [...document.querySelectorAll('.status-overlay, [data-testid=map-notice], [data-testid=busy-note], .error-box')]
      .filter((element) => !element.hidden)
      .map((element) => element.innerText)
      .join('\n'),
  );
}

async function run(state) {
  const baseUrl = await serveSampleData(state);
  const shots = process.env.TOURMAP_SCREENSHOTS;
  const page = await openPage(state);

  // ---- 1. Busy answers while the Metro view loads ----
  let apiRequests = 0;
  let refused = 0;
  let alwaysBusy = false;
  await page.route(
    (url) => url.pathname.startsWith('/api/v1/'),
    async (route) => {
      apiRequests++;
      const busyScenes = alwaysBusy && new URL(route.request().url()).pathname === '/api/v1/crowd/scenes';
      if (refused < BUSY_429 || busyScenes) {
        refused++;
        return route.fulfill({ status: 429, contentType: 'application/json', headers: { 'Retry-After': '1' }, body: busyBody(429) });
      }
      if (refused === BUSY_429) {
        refused++;
        const when = new Date(Date.now() + 1000).toUTCString();
        return route.fulfill({ status: 503, contentType: 'application/json', headers: { 'Retry-After': when }, body: busyBody(503) });
      }
      return route.continue();
    },
  );
  // The events socket, passed through to the server; kept to close it under the page.
  const eventSockets = [];
  await page.routeWebSocket(
    (url) => url.pathname === '/api/v1/events',
    (ws) => {
      ws.connectToServer();
      eventSockets.push(ws);
    },
  );
  const crowdSockets = [];
  await page.routeWebSocket(
    (url) => url.pathname === '/api/v1/crowd/stream',
    (ws) => {
      ws.connectToServer();
      crowdSockets.push(ws);
    },
  );

  const started = Date.now();
  await openApp(page, baseUrl);
  // The note appears while the first requests wait.
  await page.waitForSelector('[data-testid=busy-note]:not([hidden])', { timeout: LOAD_TIMEOUT_MS });
  const busyText = await page.locator('[data-testid=busy-note]').innerText();
  check(/busy/i.test(busyText) && /retrying/i.test(busyText), `the busy note says "${busyText}"`);
  check(!RAW.test(await visibleMessages(page)), `while busy the page shows: ${await visibleMessages(page)}`);
  if (shots) await page.screenshot({ path: join(shots, 'busy-note.png') });
  await page.waitForSelector('[data-testid=metro-map][data-status=ready]', { timeout: LOAD_TIMEOUT_MS });
  state.summary.push(`the Metro view loaded after ${BUSY_429} x 429 and 1 x 503 in ${((Date.now() - started) / 1000).toFixed(1)} s`);
  check(refused === BUSY_429 + 1, `${refused} busy answers were given`);
  await page.waitForSelector('[data-testid=busy-note][hidden]', { state: 'attached', timeout: 10_000 });
  const shown = Number(await page.locator('[data-testid=busy-note]').getAttribute('data-shown'));
  check(shown >= 1, `the busy note was shown ${shown} times`);
  const bodyText = await page.evaluate(() => document.body.innerText);
  check(!/Too Many Requests|Service Unavailable|rate_limited|HTTP \d{3}|\{"error"/.test(bodyText), 'the page shows a raw status after loading');
  check(!RAW.test(await visibleMessages(page)), `after loading the page shows: ${await visibleMessages(page)}`);
  const errors = await page.locator('.error-box, [data-testid=map-notice]:not([hidden])').count();
  check(errors === 0, `the page shows ${errors} error boxes after the busy answers`);
  state.summary.push(`busy note shown ${shown} time(s), then hidden`);

  // ---- 2. The events WebSocket is lost and comes back ----
  await page.waitForSelector('.connection[data-state=live]', { timeout: LOAD_TIMEOUT_MS });
  check(eventSockets.length === 1, `${eventSockets.length} events sockets before the close`);
  const closedAt = Date.now();
  await eventSockets[0].close({ code: 4000, reason: 'test: connection lost' });
  await page.waitForSelector('.connection[data-state=offline]', { timeout: 10_000 });
  await page.waitForSelector('.connection[data-state=live]', { timeout: 30_000 });
  check(eventSockets.length === 2, `${eventSockets.length} events sockets after the reconnect`);
  state.summary.push(`events socket reconnected after ${((Date.now() - closedAt) / 1000).toFixed(1)} s`);

  // ---- 3. Busy for longer than the client waits: plain words, the status only in Details ----
  alwaysBusy = true;
  // The Crowd view loads its scenes once, when first shown: a fresh page load.
  await page.goto(`${baseUrl}/#/crowd/office`);
  await page.waitForSelector('.view-crowd .error-box', { timeout: LOAD_TIMEOUT_MS });
  const box = await page.locator('.view-crowd .error-box').innerText();
  check(/busy/i.test(box), `the error box for a busy server says "${box}"`);
  check(!RAW.test(box), `the error box shows a raw status: "${box}"`);
  const details = await page.locator('.view-crowd .error-box details').evaluate((element) => element.textContent);
  check(/HTTP 429/.test(details), `the error box's Details say "${details}"`);
  check(!(await page.locator('.view-crowd .error-box details').evaluate((element) => element.open)), 'the Details are open');
  if (shots) await page.screenshot({ path: join(shots, 'busy-error.png') });
  state.summary.push(`busy beyond the retries: "${box.replace(/\s+/g, ' ').trim()}"`);

  // ---- 4. The crowd stream is lost and resumes ----
  alwaysBusy = false;
  await page.locator('.view-crowd .error-box button').click();
  await page.selectOption('[data-testid=crowd-resolution]', '0.5');
  await page.waitForFunction(() => Number(document.querySelector('[data-testid=crowd-canvas]')?.dataset.frames) >= 1, null, {
    timeout: FIRST_FRAME_TIMEOUT_MS,
  });
  const sockets = crowdSockets.length;
  const framesBefore = await page.locator('[data-testid=crowd-canvas]').evaluate((canvas) => Number(canvas.dataset.frames));
  await crowdSockets[sockets - 1].close({ code: 4000, reason: 'test: connection lost' });
  await page.waitForFunction(() => document.querySelector('[data-testid=crowd-canvas]')?.dataset.status === 'retrying', null, {
    timeout: 10_000,
  });
  const notice = await visibleMessages(page);
  check(!/code \d+|4000/.test(notice), `the stream notice shows a close code: "${notice}"`);
  await page.waitForFunction(
    (before) => {
      const canvas = document.querySelector('[data-testid=crowd-canvas]');
      return canvas?.dataset.status === 'streaming' && Number(canvas.dataset.frames) > before + 2;
    },
    framesBefore,
    { timeout: LOAD_TIMEOUT_MS },
  );
  check(crowdSockets.length === sockets + 1, `${crowdSockets.length - sockets} new crowd sockets after the close`);
  const notices = await page.locator('.view-crowd [data-testid=map-notice]:not([hidden])').count();
  check(notices === 0, 'the "stream interrupted" notice stays after the stream resumed');
  state.summary.push(`crowd stream resumed (${apiRequests} API requests seen)`);

  // The browser logs every 429/503 it received as a failed resource load: those are this test's.
  state.consoleErrors = state.consoleErrors.filter((text) => !/status of (429|503)/.test(text));
  checkNoConsoleErrors(state);
}

await runTest('resilience', OVERALL_TIMEOUT_MS, run);
