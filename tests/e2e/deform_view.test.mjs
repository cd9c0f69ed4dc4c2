// End-to-end test of the web client's Deform view: imports the sample data into a fresh
// database, serves it with the built web client, and drives headless Chromium: picks Monaco,
// adds a focus region in the middle of the map, drags it, and checks that the server's
// deformations were drawn (the road canvas reports a fingerprint of the positions it draws and
// how many answers it drew) and that the solver statistics show a residue.
//
// Run from the repository root: node tests/e2e/deform_view.test.mjs
// Environment: TOURMAP_BIN (build/tourmap), TOURMAP_WEB_ROOT (build/web),
// TOURMAP_DATA_DIR (../shared/data), TOURMAP_MANIFEST (scripts/sample-data.json).

import { apiJson, check, checkNoConsoleErrors, openApp, openPage, runTest, serveSampleData } from './support.mjs';

const OVERALL_TIMEOUT_MS = 90_000;
const NETWORK = 'monaco';
const CANVAS = '[data-testid=road-canvas]';
const DRAG_STEPS = 12;
const DRAG_STEP_PX = 10;

async function canvasState(page) {
  return page.locator(CANVAS).evaluate((canvas) => ({
    status: canvas.dataset.status,
    hash: canvas.dataset.positionsHash,
    requests: Number(canvas.dataset.requests),
    errors: Number(canvas.dataset.errors),
  }));
}

/** The share of the road canvas's pixels in the sea's colour (#aad3df), and the place names drawn. */
async function contextShown(page) {
  return page.locator(CANVAS).evaluate((canvas) => {
    const { data } = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height);
    let sea = 0;
    let all = 0;
    for (let i = 0; i < data.length; i += 4 * 7) {
      all++;
      if (Math.abs(data[i] - 170) < 6 && Math.abs(data[i + 1] - 211) < 6 && Math.abs(data[i + 2] - 223) < 6 && data[i + 3] > 250) sea++;
    }
    return { sea: sea / all, places: Number(canvas.dataset.placesDrawn), vertices: Number(canvas.dataset.contextVertices) };
  });
}

/** Waits until the canvas has drawn at least `count` answers and has no request in flight. */
async function waitForAnswers(page, count) {
  await page.waitForFunction(
    ({ selector, count }) => {
      const canvas = document.querySelector(selector);
      return Number(canvas?.dataset.requests) >= count && canvas?.dataset.busy === 'false';
    },
    { selector: CANVAS, count },
  );
  return canvasState(page);
}

async function run(state) {
  const baseUrl = await serveSampleData(state);

  const { roads } = await apiJson(baseUrl, '/api/v1/roads');
  check(roads.some((network) => network.id === NETWORK), `the API lists no road network ${NETWORK}`);

  const page = await openPage(state);
  await openApp(page, baseUrl, '#/deform');
  await page.waitForSelector('[data-testid=road-picker]:not([disabled])');
  const options = await page.locator('[data-testid=road-picker] option').count();
  check(options === roads.length, `the picker offers ${options} road networks, the API lists ${roads.length}`);

  await page.selectOption('[data-testid=road-picker]', NETWORK);
  await page.waitForSelector(`${CANVAS}[data-status=ready][data-network="${NETWORK}"]`);
  const hash = await page.evaluate(() => window.location.hash);
  check(hash === `#/deform/${NETWORK}`, `the route is ${hash} after picking ${NETWORK}`);
  const credits = await page.locator('.attribution').innerText();
  check(credits.includes('OpenStreetMap'), `the attribution does not credit OpenStreetMap: "${credits}"`);
  // Monaco's context layers (GET /roads/{id}/context): the sea from its coastline fills part of
  // the map, and the quarters' names are drawn.
  await page.waitForSelector(`${CANVAS}[data-context-vertices]`);
  await page.waitForFunction((selector) => Number(document.querySelector(selector)?.dataset.placesDrawn) > 0, CANVAS);
  const context = await contextShown(page);
  check(context.sea > 0.1, `the sea covers ${(100 * context.sea).toFixed(1)} % of Monaco's map`);
  check(context.places >= 3, `${context.places} place names drawn on Monaco`);
  state.summary.push(`sea on ${(100 * context.sea).toFixed(0)} % of the map, ${context.places} place names`);
  const undeformed = await canvasState(page);
  check(undeformed.requests === 0, `${undeformed.requests} deformations drawn before any focus region`);

  // Every deformation answer comes as binary positions (api/positions_binary.hpp).
  const answerTypes = [];
  const mapPointCounts = [];
  page.on('response', (response) => {
    if (!response.url().includes('/api/v1/deform/')) return;
    answerTypes.push(response.headers()['content-type'] ?? '');
    mapPointCounts.push(JSON.parse(response.request().postData() ?? '{}').map_points?.length ?? 0);
  });

  // A click in the middle of the map adds a focus region; the server's answer is drawn.
  const map = await page.locator('[data-testid=road-map]').boundingBox();
  await page.mouse.click(map.x + map.width / 2, map.y + map.height / 2);
  const focused = await waitForAnswers(page, 1);
  check(focused.hash !== undeformed.hash, 'the roads drawn did not change after adding a focus region');
  check((await page.locator('[data-testid=region-list] li').count()) === 1, 'the panel does not list the focus region');
  state.summary.push('a focus region deforms the map');
  // The region's outline is where the server's grid put the circle: its centre and 72 rim
  // points ride along as map_points. The handle is drawn where the user clicked: the focus pushes
  // its own centre aside (Monaco: 23 px), so the client moves the centre until it lands there.
  check(mapPointCounts.length > 0 && mapPointCounts.every((n) => n === 73), `map_points per request: ${mapPointCounts.join(', ')}`);
  const placed = await page.locator('.focus-handle').first().boundingBox();
  const offset = Math.hypot(placed.x + placed.width / 2 - (map.x + map.width / 2), placed.y + placed.height / 2 - (map.y + map.height / 2));
  check(offset <= 4, `the region's handle is drawn ${offset.toFixed(1)} px from the click`);
  state.summary.push(`handle ${offset.toFixed(1)} px from the click`);

  // Drag the region's centre handle: the roads must follow.
  const handle = await page.locator('.focus-handle').first().boundingBox();
  check(handle, 'no focus region handle on the map');
  const x = handle.x + handle.width / 2;
  const y = handle.y + handle.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let i = 1; i <= DRAG_STEPS; i++) await page.mouse.move(x + i * DRAG_STEP_PX, y + (i * DRAG_STEP_PX) / 2);
  await page.mouse.up();
  const dragged = await waitForAnswers(page, focused.requests + 2);
  check(dragged.hash !== focused.hash, 'the roads drawn did not change while dragging the focus region');
  check(dragged.errors === 0, `${dragged.errors} deformation requests failed`);
  check(await page.locator('[data-testid=deform-error]').isHidden(), 'an error box is shown');
  state.summary.push(`dragging it drew ${dragged.requests - focused.requests} more deformations`);
  const warped = await contextShown(page);
  check(warped.sea > 0.1 && warped.places >= 3, `after the drag the sea covers ${(100 * warped.sea).toFixed(1)} %, ${warped.places} names drawn`);
  check(answerTypes.length > 0 && answerTypes.every((type) => type === 'application/octet-stream'),
    `deformations came as ${[...new Set(answerTypes)].join(', ') || 'nothing'}, not as binary positions`);
  state.summary.push(`${answerTypes.length} answers as binary positions`);

  // The numbers are folded away until opened; the grid and solver sit behind "Advanced".
  const stats = page.locator('[data-testid=deform-stats]');
  check(!(await stats.evaluate((element) => element.open)), 'the numbers box is open before it was asked for');
  check(!(await page.locator('[data-testid=deform-advanced]').evaluate((element) => element.open)), 'the advanced options are open at first');
  check(await page.locator('[data-testid=grid-kind]').isHidden(), 'the grid choice shows without opening Advanced');
  await stats.locator('summary').click();
  const residue = Number(await stats.getAttribute('data-residue'));
  const statsText = await stats.innerText();
  check(Number.isFinite(residue) && residue > 0, `the stats box holds no residue (data-residue "${residue}")`);
  check(/Residue/.test(statsText) && /\d/.test(statsText), `the stats box shows no residue: "${statsText}"`);
  state.summary.push(`stats show residue ${Math.round(residue)}`);

  checkNoConsoleErrors(state);
}

await runTest('deform_view', OVERALL_TIMEOUT_MS, run);
