// End-to-end test of the web client's Crowd view: serves the built web client and drives
// headless Chromium through #/crowd/office, which streams server-rendered JPEG frames over
// /api/v1/crowd/stream. Checks that frames are drawn on the canvas, that a camera drag and the
// walk keys change the picture (with the animation off, so nothing else does), that the stats
// overlay shows the server's numbers, and that the resolution, mode, PoE and heat map switches
// reach the server (its stats and the picture say so). The heat map's legend shows with it; drags
// and keys that would take the eye under the floor or into a wall (the occluder boxes the API
// lists) leave it above the ground and outside every box.
//
// The server renders with software GL here: a frame can take a few hundred ms, and the first
// stream waits while the scene is built (models loaded, cluster hierarchies built), which can
// take many seconds; hence the long wait for the first frame. The picture is kept small (the
// "Half" resolution of a ~960 x 546 stage: ~480 x 273 pixels) to keep frames fast.
//
// Run from the repository root: node tests/e2e/crowd_view.test.mjs
// Environment: TOURMAP_BIN (build/tourmap), TOURMAP_WEB_ROOT (build/web),
// TOURMAP_DATA_DIR (../shared/data), TOURMAP_MANIFEST (scripts/sample-data.json).
// TOURMAP_SCREENSHOTS: a directory to save the heat map legend's screenshots in (optional).

import { join } from 'node:path';
import { STEP_TIMEOUT_MS, apiJson, check, checkNoConsoleErrors, openApp, openPage, runTest, serveSampleData } from './support.mjs';

/** ctest gives every browser test 180 s; the first frame may take up to FIRST_FRAME_TIMEOUT_MS of it. */
const OVERALL_TIMEOUT_MS = 290_000;
/** The first frame waits for the scene to be built on the server (software GL, cold caches). */
const FIRST_FRAME_TIMEOUT_MS = 120_000;
/** No new frame for this long: the server has rendered the latest view (animation off). */
const QUIET_MS = 1500;
const SCENE = 'office';
const CANVAS = '[data-testid=crowd-canvas]';
const STATS = '[data-testid=crowd-stats]';
const VIEWPORT = { width: 1300, height: 600 };

/** The eye keeps this far from a box (orbit-camera.ts BOX_MARGIN is 0.3 m; the eye is rounded to 0.1 mm). */
const BOX_CLEARANCE = 0.29;
/** The eye the user steers stays 0.5 m above the ground; pushed out of a wall towards the target, 0.2 m. */
const EYE_FLOOR = 0.2 - 1e-3;

/** The box (grown by `margin`) that holds `p`, or undefined. */
function boxHolding(p, boxes, margin) {
  return boxes.find((box) => [0, 1, 2].every((axis) => p[axis] > box.min[axis] - margin && p[axis] < box.max[axis] + margin));
}

/** Records every eye the camera reports (data-eye) from now on; eyesSeen returns them. */
async function recordEyes(page) {
  await page.locator(CANVAS).evaluate((canvas) => {
    window.eyesSeen = [];
    new MutationObserver(() => window.eyesSeen.push(canvas.dataset.eye)).observe(canvas, { attributeFilter: ['data-eye'] });
  });
}

async function eyesSeen(page) {
  const eyes = await page.evaluate(() => window.eyesSeen.splice(0));
  return eyes.map((text) => text.split(',').map(Number));
}

/** Fails unless every eye is above the ground and outside every occluder box. */
function checkEyes(eyes, boxes, what) {
  check(eyes.length > 0, `${what}: the camera reported no eye`);
  for (const eye of eyes) {
    check(eye.every(Number.isFinite), `${what}: the eye is [${eye}]`);
    check(eye[1] >= EYE_FLOOR, `${what}: the eye went down to y = ${eye[1]} (under the floor)`);
    const box = boxHolding(eye, boxes, BOX_CLEARANCE);
    check(!box, `${what}: the eye [${eye}] is in the occluder box ${JSON.stringify(box)}`);
  }
}

/** The server's heat ramp (core/render/crowd_shaders.hpp heat()), as CSS rgb() of 0..255. */
function shaderHeat(t) {
  const channel = (centre) => Math.round(Math.min(1, Math.max(0, 1.5 - Math.abs(4 * t - centre))) * 255);
  return `rgb(${channel(3)}, ${channel(2)}, ${channel(1)})`;
}

/** A left-button drag by (dx, dy) in 20 steps. */
async function drag(page, fromX, fromY, dx, dy) {
  await page.mouse.move(fromX, fromY);
  await page.mouse.down();
  for (let i = 1; i <= 20; i++) await page.mouse.move(fromX + (dx * i) / 20, fromY + (dy * i) / 20);
  await page.mouse.up();
}

async function frameCount(page) {
  return page.locator(CANVAS).evaluate((canvas) => Number(canvas.dataset.frames));
}

async function statsState(page) {
  return page.locator(STATS).evaluate((stats) => ({
    frame: Number(stats.dataset.frame),
    scene: stats.dataset.scene,
    mode: stats.dataset.mode,
    poe: Number(stats.dataset.poe),
    triangles: Number(stats.dataset.triangles),
    width: Number(stats.dataset.width),
    height: Number(stats.dataset.height),
    latencyMs: Number(stats.dataset.latencyMs),
    quality: stats.dataset.quality,
    qualityLevel: Number(stats.dataset.qualityLevel),
  }));
}

/**
 * A fingerprint of the canvas pixels (FNV-1a over a subsample of RGB) and how many distinct
 * colours it has (a blank canvas has one).
 */
async function snapshot(page) {
  return page.locator(CANVAS).evaluate((canvas) => {
    const { data } = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height);
    let hash = 0x811c9dc5;
    const colours = new Set();
    for (let i = 0; i < data.length; i += 4) {
      hash = Math.imul(hash ^ data[i], 0x01000193);
      hash = Math.imul(hash ^ data[i + 1], 0x01000193);
      hash = Math.imul(hash ^ data[i + 2], 0x01000193);
      if (colours.size < 4096 && i % 64 === 0) colours.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
    }
    return { hash: (hash >>> 0).toString(16), colours: colours.size, width: canvas.width, height: canvas.height };
  });
}

/**
 * Waits until at least `minFrames` frames are drawn, then until no new frame arrives for
 * QUIET_MS and the stats box describes the last frame drawn; returns the frame count.
 */
async function waitForQuiet(page, minFrames, timeoutMs = STEP_TIMEOUT_MS) {
  await page.waitForFunction((n) => Number(document.querySelector('[data-testid=crowd-canvas]')?.dataset.frames) >= n, minFrames, {
    timeout: timeoutMs,
  });
  const deadline = Date.now() + STEP_TIMEOUT_MS;
  let last = await frameCount(page);
  let since = Date.now();
  while (Date.now() < deadline) {
    await page.waitForTimeout(100);
    const now = await frameCount(page);
    const synced = await page.evaluate(
      () =>
        document.querySelector('[data-testid=crowd-stats]')?.dataset.frame ===
        document.querySelector('[data-testid=crowd-canvas]')?.dataset.frameId,
    );
    if (now !== last) {
      last = now;
      since = Date.now();
    } else if (synced && Date.now() - since >= QUIET_MS) {
      return now;
    }
  }
  check(false, `the stream did not settle: frames kept arriving for ${STEP_TIMEOUT_MS / 1000} s with the animation off`);
}

/** Waits for the stats of a frame rendered with `expected` (mode, poe…), at most one step. */
async function waitForStats(page, expected) {
  await page.waitForFunction(
    (want) => {
      const data = document.querySelector('[data-testid=crowd-stats]')?.dataset ?? {};
      return Object.entries(want).every(([key, value]) => data[key] === String(value));
    },
    expected,
    { timeout: STEP_TIMEOUT_MS },
  );
}

async function run(state) {
  const baseUrl = await serveSampleData(state);

  const catalog = await apiJson(baseUrl, '/api/v1/crowd/scenes');
  const scene = catalog.scenes.find((candidate) => candidate.id === SCENE);
  check(scene, `the API lists no crowd scene ${SCENE}`);
  check(catalog.modes.includes('vdr') && catalog.modes.includes('vdr+oc'), `the API offers the modes ${catalog.modes}`);

  const page = await openPage(state);
  await page.setViewportSize(VIEWPORT);
  await openApp(page, baseUrl, `#/crowd/${SCENE}`);
  // Half resolution before the first frame: faster software rendering.
  await page.selectOption('[data-testid=crowd-resolution]', '0.5');
  await page.waitForSelector('[data-testid=crowd-scene]:not([disabled])');
  const options = await page.locator('[data-testid=crowd-scene] option').count();
  check(options === catalog.scenes.length, `the picker offers ${options} scenes, the API lists ${catalog.scenes.length}`);
  check((await page.locator('[data-testid=crowd-scene]').inputValue()) === SCENE, `the picker does not show ${SCENE}`);
  const credits = await page.locator('.view-crowd .attribution').innerText();
  // A credit may cover several models ("Horse, Donkey, Cow").
  const credited = (entry) => entry.model.split(',').some((name) => scene.models.includes(name.trim()));
  check(catalog.attribution.some(credited), `the API credits none of the models of ${SCENE}: ${scene.models}`);
  for (const credit of catalog.attribution.filter(credited)) {
    check(credits.includes(credit.text), `the view does not credit ${credit.model}: "${credits}"`);
  }

  // The first frame: the scene is built on the server first (see the comment at the top).
  const started = Date.now();
  await page.waitForFunction(
    (id) => {
      const canvas = document.querySelector('[data-testid=crowd-canvas]');
      const stats = document.querySelector('[data-testid=crowd-stats]');
      return Number(canvas?.dataset.frames) >= 1 && stats?.dataset.scene === id;
    },
    SCENE,
    { timeout: FIRST_FRAME_TIMEOUT_MS },
  );
  state.summary.push(`first frame after ${((Date.now() - started) / 1000).toFixed(1)} s`);

  // Stop the animation: from now on only our changes change the picture.
  await page.locator('[data-testid=crowd-animate]').uncheck();
  const settled = await waitForQuiet(page, 1);
  const first = await snapshot(page);
  const stats = await statsState(page);
  check(first.colours > 8, `the canvas shows ${first.colours} colours: nothing was drawn`);
  check(stats.mode === 'vdr+oc', `the first frames were rendered in mode ${stats.mode}, not the default vdr+oc`);
  check(stats.triangles > 0, `the stats report ${stats.triangles} triangles`);
  // The numbers are folded (they would cover the picture): open them to read them.
  await page.locator(STATS).evaluate((details) => (details.open = true));
  const trianglesText = await page.locator(`${STATS} [data-stat=triangles] dd`).innerText();
  check(/\d/.test(trianglesText), `the stats overlay shows triangles as "${trianglesText}"`);
  check(Number.isFinite(stats.latencyMs) && stats.latencyMs > -1000 && stats.latencyMs < 60_000, `frame latency ${stats.latencyMs} ms`);
  // Half of the stage's CSS pixels, as the server rendered them and as drawn.
  const stage = await page.locator('.crowd-stage').boundingBox();
  check(
    Math.abs(stats.width - stage.width / 2) <= 2 && Math.abs(stats.height - stage.height / 2) <= 2,
    `frames of ${stats.width} x ${stats.height} for a ${stage.width} x ${stage.height} stage at half resolution`,
  );
  check(first.width === stats.width && first.height === stats.height, `the canvas is ${first.width} x ${first.height}, the frame ${stats.width} x ${stats.height}`);
  await page.waitForTimeout(1000);
  check((await snapshot(page)).hash === first.hash, 'the picture changed with the animation off and the camera still');
  state.summary.push(`${stats.width} x ${stats.height}, ${stats.triangles.toLocaleString('en')} triangles (${trianglesText})`);

  // Drag on the canvas: the camera orbits, the server renders the new view.
  const box = await page.locator(CANVAS).boundingBox();
  const x = box.x + box.width / 2;
  const y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(x + i * 12, y + i * 3);
  await page.mouse.up();
  const dragged = await waitForQuiet(page, settled + 1);
  const orbited = await snapshot(page);
  check(orbited.hash !== first.hash, 'the picture did not change after dragging the camera');
  // At rest after the drag: the last frame is at full size and quality, whatever the drag's were.
  const rest = await statsState(page);
  check(
    rest.qualityLevel === 0 && orbited.width === first.width && orbited.height === first.height,
    `after the drag the picture rests at ${orbited.width} x ${orbited.height} (level ${rest.qualityLevel}, ${rest.quality}), not ${first.width} x ${first.height}`,
  );
  state.summary.push('a drag orbits the camera');

  // The canvas has the focus now (the drag gave it); W walks forward.
  check(await page.locator(CANVAS).evaluate((canvas) => canvas === document.activeElement), 'the canvas has no keyboard focus after a drag');
  await page.keyboard.down('KeyW');
  await page.waitForTimeout(400);
  await page.keyboard.up('KeyW');
  const walked = await waitForQuiet(page, dragged + 1);
  const moved = await snapshot(page);
  check(moved.hash !== orbited.hash, 'the picture did not change after walking with W');
  state.summary.push('W walks');

  // VDR+OC -> VDR: the same view without occlusion culling draws at least as many triangles.
  const withOc = await statsState(page);
  await page.locator('[data-testid=crowd-mode] [data-mode="vdr"]').click();
  await waitForStats(page, { mode: 'vdr' });
  // Occlusion culling is conservative: the same picture, so the server sends its stats only and
  // the canvas keeps the frame it has (issue 18: an unchanged frame is not encoded nor sent).
  const vdrFrames = await waitForQuiet(page, walked);
  const vdr = await statsState(page);
  check(vdrFrames === walked && (await snapshot(page)).hash === moved.hash, `VDR drew a new picture (${vdrFrames} frames, ${walked} before)`);
  check(
    (await page.locator('[data-testid=crowd-mode] [data-mode="vdr"]').getAttribute('aria-pressed')) === 'true',
    'the VDR button is not shown pressed',
  );
  check(vdr.triangles >= withOc.triangles, `VDR draws ${vdr.triangles} triangles, VDR+OC ${withOc.triangles}: occlusion culling added triangles`);
  state.summary.push(`vdr: ${vdr.triangles.toLocaleString('en')} triangles, vdr+oc: ${withOc.triangles.toLocaleString('en')}`);

  // The largest pixel error: a coarser cut, fewer triangles.
  await page.locator('[data-testid=crowd-poe]').fill('1000');
  const poe = Number(await page.locator('[data-testid=crowd-poe]').getAttribute('data-value'));
  check(poe >= 10, `the PoE slider's end is ${poe} px`);
  await waitForStats(page, { mode: 'vdr', poe });
  const coarseFrames = await waitForQuiet(page, vdrFrames + 1);
  const coarse = await statsState(page);
  check(coarse.triangles < vdr.triangles, `PoE ${poe} draws ${coarse.triangles} triangles, PoE ${vdr.poe} ${vdr.triangles}`);
  state.summary.push(`PoE ${poe}: ${coarse.triangles.toLocaleString('en')} triangles`);

  // The heat map colours the same view differently.
  const plain = await snapshot(page);
  await page.locator('[data-testid=crowd-heatmap]').check();
  await waitForQuiet(page, coarseFrames + 1);
  const heat = await snapshot(page);
  check(heat.hash !== plain.hash, 'the picture did not change with the heat map on');
  state.summary.push('heat map');

  // Its legend: shown with it, the server's ramp from the coarsest (t = 0) to full detail (t = 1).
  const legend = page.locator('[data-testid=crowd-heat-legend]');
  check(await legend.isVisible(), 'the heat map legend is not shown with the heat map on');
  const legendText = await legend.innerText();
  check(/fewer triangles/i.test(legendText) && /full detail/i.test(legendText), `the legend says "${legendText}"`);
  const ramp = await legend.locator('.crowd-heat-ramp').evaluate((element) => getComputedStyle(element).backgroundImage);
  const rampColours = ramp.match(/rgb\([^)]*\)/g) ?? [];
  const expected = Array.from({ length: 9 }, (_, i) => shaderHeat(i / 8));
  check(JSON.stringify(rampColours) === JSON.stringify(expected), `the legend's ramp ${rampColours} is not the renderer's ${expected}`);
  const shots = process.env.TOURMAP_SCREENSHOTS;
  if (shots) {
    for (const [name, size] of [['desktop', { width: 1280, height: 800 }], ['phone', { width: 390, height: 844 }]]) {
      await page.setViewportSize(size);
      await waitForQuiet(page, (await frameCount(page)) + 1, FIRST_FRAME_TIMEOUT_MS);
      await page.screenshot({ path: join(shots, `crowd-heat-legend-${name}.png`) });
    }
    await page.setViewportSize(VIEWPORT);
    await waitForQuiet(page, (await frameCount(page)) + 1);
  }
  await page.locator('[data-testid=crowd-heatmap]').uncheck();
  check(!(await legend.isVisible()), 'the heat map legend stays with the heat map off');
  await page.locator('[data-testid=crowd-heatmap]').check();
  check(await legend.isVisible(), 'the heat map legend is not back with the heat map on again');
  state.summary.push('heat legend');

  // The camera stays above the floor and out of the walls, whatever the drags and keys ask.
  const boxes = scene.occluder_boxes;
  check(Array.isArray(boxes) && boxes.length === scene.occluders && boxes.length > 0, `the API lists ${boxes?.length} occluder boxes of ${scene.occluders}`);
  await recordEyes(page);
  await page.locator(CANVAS).focus();
  await page.keyboard.press('Home');
  // Drag up by 400 px: the orbit would take the eye 80 degrees below the target, far under the floor.
  await drag(page, x, y + 200, 0, -400);
  checkEyes(await eyesSeen(page), boxes, 'dragging down to the floor');
  const floorEye = (await page.locator(CANVAS).getAttribute('data-eye')).split(',').map(Number);
  check(floorEye[1] < 1, `the drag did not bring the eye near the floor (y = ${floorEye[1]}): the test tests nothing`);
  // Down with Q (the target to the ground), close in with +, then walk through the rooms and along them.
  await page.keyboard.down('KeyQ');
  await page.waitForTimeout(500);
  await page.keyboard.up('KeyQ');
  for (let i = 0; i < 30; i++) await page.keyboard.press('Equal');
  for (const [key, ms] of [['KeyW', 2500], ['KeyD', 2500], ['KeyS', 2500], ['KeyA', 1500]]) {
    await page.keyboard.down(key);
    await page.waitForTimeout(ms);
    await page.keyboard.up(key);
  }
  const walk = await eyesSeen(page);
  checkEyes(walk, boxes, 'walking through the office close to the floor');
  // Orbit all the way around close to the floor: the eye swings through the walls of the room.
  await drag(page, x - 300, y, 800, 0);
  const swing = await eyesSeen(page);
  checkEyes(swing, boxes, 'orbiting close to the floor');
  // Far out, then down again (the wheel, a drag): a long way from the target, close to the floor.
  for (let i = 0; i < 10; i++) await page.mouse.wheel(0, 400);
  await drag(page, x, y + 200, 0, -400);
  checkEyes(await eyesSeen(page), boxes, 'zooming out and down');
  await waitForQuiet(page, 1);
  const low = await snapshot(page);
  check(low.colours > 8, `the view from close to the floor shows ${low.colours} colours`);
  state.summary.push(`camera: ${walk.length + swing.length} eyes while walking and orbiting near the floor, all above it and out of the ${boxes.length} walls`);

  let hash = await page.evaluate(() => window.location.hash);
  check(hash === `#/crowd/${SCENE}`, `the route is ${hash}`);

  // Every other scene streams too (the picker switches scenes; the server prepares each once).
  for (const other of catalog.scenes.filter((candidate) => candidate.id !== SCENE)) {
    const before = await snapshot(page);
    const switched = Date.now();
    await page.selectOption('[data-testid=crowd-scene]', other.id);
    await page.waitForFunction(
      (id) => document.querySelector('[data-testid=crowd-stats]')?.dataset.scene === id,
      other.id,
      { timeout: FIRST_FRAME_TIMEOUT_MS },
    );
    await waitForQuiet(page, (await frameCount(page)) + 0);
    const shown = await snapshot(page);
    const otherStats = await statsState(page);
    check(shown.colours > 8 && shown.hash !== before.hash, `the ${other.id} scene shows no new picture`);
    check(otherStats.triangles > 0, `the ${other.id} scene reports ${otherStats.triangles} triangles`);
    hash = await page.evaluate(() => window.location.hash);
    check(hash === `#/crowd/${other.id}`, `after picking ${other.id} the route is ${hash}`);
    state.summary.push(`${other.id}: first frame after ${((Date.now() - switched) / 1000).toFixed(1)} s, ${otherStats.triangles.toLocaleString('en')} triangles`);
  }
  const notices = await page.locator('.view-crowd [data-testid=map-notice]:not([hidden])').count();
  check(notices === 0, `the view shows a notice: ${notices ? await page.locator('.view-crowd [data-testid=map-notice]').innerText() : ''}`);
  checkNoConsoleErrors(state);
}

await runTest('crowd_view', OVERALL_TIMEOUT_MS, run);
