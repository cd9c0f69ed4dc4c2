// End-to-end test of the web client's Metro view: imports the sample data into a fresh
// database, serves it with the built web client, and drives headless Chromium through the
// city picker, checking that every station (and, for Vienna, every POI) is drawn.
//
// Run from the repository root: node tests/e2e/metro_view.test.mjs
// Environment: TOURMAP_BIN (build/tourmap), TOURMAP_WEB_ROOT (build/web),
// TOURMAP_DATA_DIR (../shared/data), TOURMAP_MANIFEST (scripts/sample-data.json).

import { STEP_TIMEOUT_MS, apiJson, check, checkNoConsoleErrors, openApp, openPage, runTest, serveSampleData } from './support.mjs';

const OVERALL_TIMEOUT_MS = 90_000;
const FIRST_CITY = 'vienna';
const SECOND_CITY = 'lisbon';

/** Picks a city and waits until the map says it has drawn it; returns the drawn markers. */
async function pickCity(page, cityId) {
  await page.selectOption('[data-testid=city-picker]', cityId);
  await page.waitForSelector(`[data-testid=metro-map][data-status=ready][data-city="${cityId}"]`, {
    timeout: STEP_TIMEOUT_MS,
  });
  return {
    stations: await page.locator('g.station').count(),
    pois: await page.locator('.poi').count(),
    hash: await page.evaluate(() => window.location.hash),
  };
}

async function run(state) {
  const baseUrl = await serveSampleData(state);

  const { cities } = await apiJson(baseUrl, '/api/v1/cities');
  const city = (id) => cities.find((candidate) => candidate.id === id);
  check(city(FIRST_CITY) && city(SECOND_CITY), `the API lists no ${FIRST_CITY} or no ${SECOND_CITY}`);
  const first = city(FIRST_CITY).counts;
  const second = city(SECOND_CITY).counts;
  check(first.stations > 0 && first.pois > 0, `${FIRST_CITY} has no stations or no POIs in the API`);
  check(second.stations > 0 && second.stations !== first.stations, `${SECOND_CITY} must have another station count`);

  const page = await openPage(state);
  await openApp(page, baseUrl);
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

  checkNoConsoleErrors(state);
}

await runTest('metro_view', OVERALL_TIMEOUT_MS, run);
