// End-to-end test of the web client's layout on a phone (390 x 844, touch) and on a desktop
// (1280 x 800), for the Metro, Deform and Crowd views:
//   - a first visit shows the view's introduction; "Got it" dismisses it for good (localStorage)
//     and the "?" button brings it back;
//   - the map covers at least 70 % of the viewport (sampled with elementFromPoint: panels,
//     buttons and credits over the map do not count);
//   - no two visible controls (button, input, select, summary, a[href]) overlap, with the
//     controls folded, unfolded and with every <details> open;
//   - on the phone every control is at least 44 x 44 px (a checkbox counts with its label; links
//     inside the credits' sentences are inline text, which WCAG 2.5.8 exempts);
//   - no number (.num, output, dd; a dd.words holds words) breaks over two lines;
//   - a pinch zooms the map (Metro, Deform) or moves the camera closer (Crowd), and a tap on the
//     Deform map adds a focus region;
//   - on the phone no station's centre is covered by a POI pin or a cluster marker;
//   - axe-core finds no serious or critical violation.
//
// Run from the repository root: node tests/e2e/phone_layout.test.mjs
// Environment: TOURMAP_BIN, TOURMAP_WEB_ROOT, TOURMAP_DATA_DIR, TOURMAP_MANIFEST (see support.mjs);
// TOURMAP_E2E_SCREENSHOTS: a directory for a screenshot per view and size (optional).

import { mkdirSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { STEP_TIMEOUT_MS, check, checkNoConsoleErrors, runTest, serveSampleData } from './support.mjs';

const OVERALL_TIMEOUT_MS = 300_000;
const FIRST_FRAME_TIMEOUT_MS = 120_000;
const MIN_MAP_SHARE = 0.7;
const MIN_TAP_PX = 44;

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { chromium } = require('playwright-core');
const AXE_PATH = fileURLToPath(new URL('../../web/node_modules/axe-core/axe.min.js', import.meta.url));
const LOCAL_HOSTS = new Set(['127.0.0.1', 'localhost', '[::1]']);

const SIZES = [
  { name: 'phone', touch: true, options: { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, deviceScaleFactor: 1 } },
  { name: 'desktop', touch: false, options: { viewport: { width: 1280, height: 800 } } },
];

const VIEWS = [
  { name: 'metro', hash: '#/metro/vienna', map: '[data-testid=metro-map]', ready: '[data-testid=metro-map][data-status=ready][data-city=vienna]' },
  { name: 'deform', hash: '#/deform/monaco', map: '[data-testid=road-map]', ready: '[data-testid=road-canvas][data-status=ready]' },
  { name: 'crowd', hash: '#/crowd', map: '[data-testid=crowd-canvas]', ready: '[data-testid=crowd-canvas]:not([data-frames="0"])[data-frames]' },
];

/** A fresh browser context (empty localStorage: a first visit) with one page. */
async function newPage(state, browser, size) {
  const context = await browser.newContext(size.options);
  const page = await context.newPage();
  page.setDefaultTimeout(STEP_TIMEOUT_MS);
  await page.route(
    (url) => !LOCAL_HOSTS.has(url.hostname),
    (route) => route.fulfill({ status: 200, contentType: 'image/svg+xml', body: '<svg xmlns="http://www.w3.org/2000/svg" width="4" height="4"/>' }),
  );
  page.on('console', (message) => {
    if (message.type() === 'error') state.consoleErrors.push(message.text());
  });
  page.on('pageerror', (error) => state.consoleErrors.push(`uncaught: ${error.message}`));
  return { context, page };
}

/** The share of the viewport where the topmost element is the map (or part of it). */
function mapShare(page, mapSelector) {
  return page.evaluate((selector) => {
    const map = document.querySelector(selector);
    const steps = 40;
    let hits = 0;
    for (let i = 0; i < steps; i++) {
      for (let j = 0; j < steps; j++) {
        const x = ((i + 0.5) / steps) * window.innerWidth;
        const y = ((j + 0.5) / steps) * window.innerHeight;
        const top = document.elementFromPoint(x, y);
        if (top && map && (top === map || map.contains(top))) hits++;
      }
    }
    return hits / (steps * steps);
  }, mapSelector);
}

/**
 * The visible controls: their rectangles (clipped by scrolling ancestors), their tap target (a
 * checkbox's or radio's label, if any) and a name for messages.
 */
function visibleControls(page) {
  return page.evaluate(() => {
    const clip = (element, rect) => {
      let r = { left: rect.left, top: rect.top, right: rect.right, bottom: rect.bottom };
      for (let parent = element.parentElement; parent; parent = parent.parentElement) {
        const style = getComputedStyle(parent);
        if (style.overflow === 'visible' && style.overflowX === 'visible' && style.overflowY === 'visible') continue;
        const p = parent.getBoundingClientRect();
        r = { left: Math.max(r.left, p.left), top: Math.max(r.top, p.top), right: Math.min(r.right, p.right), bottom: Math.min(r.bottom, p.bottom) };
      }
      r = { left: Math.max(r.left, 0), top: Math.max(r.top, 0), right: Math.min(r.right, innerWidth), bottom: Math.min(r.bottom, innerHeight) };
      return r.right > r.left && r.bottom > r.top ? r : null;
    };
    const name = (element) => {
      const id = element.dataset.testid ?? element.id ?? '';
      const text = (element.getAttribute('aria-label') ?? element.textContent ?? '').trim().slice(0, 30);
      return `${element.tagName.toLowerCase()}${id ? `#${id}` : ''}${element.className && typeof element.className === 'string' ? `.${element.className.split(' ')[0]}` : ''} "${text}"`;
    };
    const controls = [];
    for (const element of document.querySelectorAll('button, input, select, summary, a[href]')) {
      // checkVisibility: also what a closed <details> hides (content-visibility), which still has boxes.
      if (!element.checkVisibility({ visibilityProperty: true, contentVisibilityAuto: true }) || element.closest('[hidden]')) continue;
      const rect = element.getBoundingClientRect();
      if (rect.width === 0 || rect.height === 0) continue;
      const clipped = clip(element, rect);
      if (!clipped) continue;
      const label = (element.type === 'checkbox' || element.type === 'radio') ? element.closest('label') : null;
      const target = (label ?? element).getBoundingClientRect();
      controls.push({
        name: name(element),
        clipped,
        width: target.width,
        height: target.height,
        inlineText: element.tagName === 'A' && element.closest('.attribution') !== null,
        index: controls.length,
      });
      element.dataset.e2eIndex = String(controls.length - 1);
    }
    // Pairs that overlap by more than a pixel each way (neither inside the other).
    const overlaps = [];
    const all = [...document.querySelectorAll('[data-e2e-index]')];
    for (let i = 0; i < controls.length; i++) {
      for (let j = i + 1; j < controls.length; j++) {
        const [a, b] = [controls[i].clipped, controls[j].clipped];
        const w = Math.min(a.right, b.right) - Math.max(a.left, b.left);
        const h = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
        if (w <= 1 || h <= 1) continue;
        const [ea, eb] = [all.find((e) => e.dataset.e2eIndex === String(i)), all.find((e) => e.dataset.e2eIndex === String(j))];
        if (ea?.contains(eb) || eb?.contains(ea)) continue;
        overlaps.push(`${controls[i].name} and ${controls[j].name}`);
      }
    }
    for (const element of all) delete element.dataset.e2eIndex;
    return { controls, overlaps };
  });
}

/** Numbers (.num, output, dd but dd.words) shown on more than one line. */
function wrappedNumbers(page) {
  return page.evaluate(() => {
    const wrapped = [];
    let checked = 0;
    for (const element of document.querySelectorAll('.num, output, dd:not(.words)')) {
      if (!element.checkVisibility({ visibilityProperty: true, contentVisibilityAuto: true }) || element.textContent.trim() === '') continue;
      const range = document.createRange();
      range.selectNodeContents(element);
      const tops = new Set([...range.getClientRects()].filter((r) => r.width > 0).map((r) => Math.round(r.top)));
      checked++;
      if (tops.size > 1) wrapped.push(`"${element.textContent.trim()}" on ${tops.size} lines`);
    }
    return { checked, wrapped };
  });
}

/** Stations whose centre is under a POI pin or a cluster marker (phone: a tap there misses the station). */
function coveredStations(page) {
  return page.evaluate(() => {
    const covered = [];
    let checked = 0;
    const map = document.querySelector('[data-testid=metro-map]');
    for (const station of document.querySelectorAll('g.station')) {
      const box = station.getBoundingClientRect();
      const x = box.x + box.width / 2;
      const y = box.y + box.height / 2;
      if (x < 0 || y < 0 || x >= innerWidth || y >= innerHeight) continue;
      const top = document.elementFromPoint(x, y);
      if (!top || !map.contains(top)) continue; // under a panel, not the map
      checked++;
      const hit = top.closest('.station, .poi, .cluster-marker, [data-cluster], .cluster');
      if (hit && hit !== station && !hit.classList.contains('station')) covered.push(station.dataset.id);
    }
    return { checked, covered };
  });
}

async function axeViolations(page) {
  await page.addScriptTag({ path: AXE_PATH });
  return page.evaluate(async () => {
    const result = await window.axe.run(document, { resultTypes: ['violations'] });
    return result.violations
      .filter((v) => v.impact === 'serious' || v.impact === 'critical')
      .map((v) => `${v.id} (${v.impact}): ${v.nodes.slice(0, 3).map((n) => n.target.join(' ')).join(', ')}`);
  });
}

/** A two-finger pinch (fingers moving apart) at the centre of `selector`, through CDP touch events. */
async function pinchOut(page, selector) {
  const box = await page.locator(selector).boundingBox();
  const cx = box.x + box.width / 2;
  const cy = box.y + box.height / 2;
  const session = await page.context().newCDPSession(page);
  const points = (d) => [
    { x: cx - d, y: cy, id: 0 },
    { x: cx + d, y: cy, id: 1 },
  ];
  await session.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: points(30) });
  for (let d = 40; d <= 120; d += 10) {
    await session.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: points(d) });
    await page.waitForTimeout(16);
  }
  await session.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await session.detach();
}

const mapScale = (page, selector) =>
  page.evaluate((s) => document.querySelector(`${s} .map-world`)?.getScreenCTM()?.a ?? null, selector);

/** Unfolds or folds the controls' sheet (only a phone has one to fold). */
async function setSheet(page, view, open) {
  await page.evaluate(
    ([name, wanted]) => {
      const sheet = document.querySelector(`.view-${name} .sheet`);
      const handle = sheet?.querySelector('.sheet-handle');
      if (sheet && handle && getComputedStyle(handle).display !== 'none' && (sheet.dataset.open === 'true') !== wanted) handle.click();
    },
    [view, open],
  );
  await page.waitForTimeout(300);
}

/**
 * The schematics of Vienna and of Monaco (wide for its height, with long names at its ends)
 * fitted to the map with the controls folded: every station name shown lies whole on the map,
 * none cut off at its edge (names keep their size in pixels, so the fit makes room for them or
 * leaves out the ones it cannot).
 */
async function namesOnTheMap(page, view, label) {
  const results = [];
  for (const city of ['vienna', 'monaco']) {
    if (city !== 'vienna') {
      await page.evaluate((hash) => (window.location.hash = hash), `#/metro/${city}`);
      await page.waitForSelector(`${view.map}[data-status=ready][data-city=${city}]`);
      await setSheet(page, view.name, true);
      await page.click('[data-testid=mode-switch] [data-value=octilinear]');
    }
    await page.waitForSelector(`${view.map}[data-mode=octilinear][data-transition=idle][data-layout=ready]`);
    await setSheet(page, view.name, false);
    await page.click(`.view-${view.name} .zoom-fit`);
    await page.waitForTimeout(1500); // the fit, and its refits for the names
    const { shown, cut } = await page.evaluate((selector) => {
      const map = document.querySelector(selector).getBoundingClientRect();
      const names = [...document.querySelectorAll(`${selector} text.station-label`)].filter((t) => t.getAttribute('visibility') === 'visible');
      const out = names.filter((t) => {
        const r = t.getBoundingClientRect();
        return r.width > 0 && (r.left < map.left - 0.5 || r.right > map.right + 0.5 || r.top < map.top - 0.5 || r.bottom > map.bottom + 0.5);
      });
      return { shown: names.length, cut: out.map((t) => t.textContent) };
    }, view.map);
    // Vienna's whole schematic is below the smallest zoom the server names stations for on a
    // phone (it shows none until one zooms in); Monaco's is named at its fit.
    if (city === 'monaco') check(shown > 10, `${label}: only ${shown} station names shown on ${city}'s schematic`);
    check(cut.length === 0, `${label}: ${city}'s schematic cuts off ${cut.length} of ${shown} names at the map's edge: ${cut.slice(0, 6).join(', ')}`);
    results.push(`${city} ${shown} names whole`);
  }
  return `schematic: ${results.join(', ')}`;
}

async function checkLayout(page, view, size, when) {
  const { controls, overlaps } = await visibleControls(page);
  check(overlaps.length === 0, `${view.name} ${size.name} (${when}): controls overlap: ${overlaps.slice(0, 6).join('; ')}`);
  if (size.touch) {
    const small = controls.filter((c) => !c.inlineText && (c.width < MIN_TAP_PX - 0.5 || c.height < MIN_TAP_PX - 0.5));
    check(
      small.length === 0,
      `${view.name} ${size.name} (${when}): ${small.length} tap targets under ${MIN_TAP_PX} px: ${small
        .slice(0, 6)
        .map((c) => `${c.name} ${c.width.toFixed(0)}x${c.height.toFixed(0)}`)
        .join('; ')}`,
    );
  }
  return controls.length;
}

/** Opens every <details> of the view (Advanced, numbers, legend …). */
async function openAllDetails(page, view) {
  await page.evaluate((name) => {
    for (const details of document.querySelectorAll(`.view-${name} details`)) details.open = true;
  }, view.name);
  await page.waitForTimeout(300);
}

async function closeOverlays(page, view) {
  await page.evaluate((name) => {
    for (const details of document.querySelectorAll(`.view-${name} .map-area details, .view-${name} .advanced`)) details.open = false;
  }, view.name);
}

async function checkView(state, browser, baseUrl, view, size, screenshots) {
  const { context, page } = await newPage(state, browser, size);
  const label = `${view.name} ${size.name}`;
  await page.goto(`${baseUrl}/${view.hash}`);
  await page.waitForSelector(view.ready, { timeout: view.name === 'crowd' ? FIRST_FRAME_TIMEOUT_MS : STEP_TIMEOUT_MS });

  // The first visit: the introduction, dismissed for good, back from "?".
  const intro = page.locator(`[data-testid=intro-${view.name}]`);
  check(await intro.isVisible(), `${label}: no introduction on the first visit`);
  if (screenshots) await page.screenshot({ path: join(screenshots, `phone_layout_${view.name}_${size.name}_intro.png`) });
  await intro.locator('.intro-close').click();
  check(await intro.isHidden(), `${label}: "Got it" did not close the introduction`);
  await page.reload();
  await page.waitForSelector(view.ready, { timeout: view.name === 'crowd' ? FIRST_FRAME_TIMEOUT_MS : STEP_TIMEOUT_MS });
  check(await intro.isHidden(), `${label}: the introduction came back after a reload`);
  await page.locator(`.view-${view.name} .help-button`).click();
  check(await intro.isVisible(), `${label}: the "?" button does not show the introduction`);
  await intro.locator('.intro-close').click();
  await setSheet(page, view.name, false);
  await page.waitForTimeout(view.name === 'crowd' ? 1500 : 600);

  // The map fills the screen.
  const share = await mapShare(page, view.map);
  if (screenshots) await page.screenshot({ path: join(screenshots, `phone_layout_${view.name}_${size.name}.png`) });
  check(share >= MIN_MAP_SHARE, `${label}: the map shows on ${(100 * share).toFixed(1)} % of the screen (at least ${100 * MIN_MAP_SHARE} % wanted)`);
  let controls = await checkLayout(page, view, size, 'controls folded');

  // Touch: a pinch zooms; on Deform a tap adds a focus region.
  if (size.touch) {
    if (view.name === 'crowd') {
      const before = await page.locator(view.map).getAttribute('data-eye');
      await pinchOut(page, view.map);
      await page.waitForTimeout(300);
      const after = await page.locator(view.map).getAttribute('data-eye');
      check(before && after && before !== after, `${label}: a pinch did not move the camera (eye ${before} -> ${after})`);
    } else {
      const before = await mapScale(page, view.map);
      await pinchOut(page, view.map);
      await page.waitForTimeout(400);
      const after = await mapScale(page, view.map);
      check(before && after && after > before * 1.2, `${label}: a pinch did not zoom in (scale ${before} -> ${after})`);
      await page.click(`.view-${view.name} .zoom-fit`);
      await page.waitForTimeout(500);
    }
    if (view.name === 'deform') {
      const box = await page.locator(view.map).boundingBox();
      await page.touchscreen.tap(box.x + box.width / 2, box.y + box.height / 2);
      await page.waitForFunction(() => document.querySelectorAll('[data-testid=region-list] li').length === 1);
      await page.waitForFunction(() => document.querySelector('[data-testid=deform-stats]')?.dataset.residue !== '');
    }
    if (view.name === 'metro') {
      const { checked, covered } = await coveredStations(page);
      check(checked > 20, `${label}: only ${checked} stations on screen to tap`);
      check(covered.length === 0, `${label}: ${covered.length} of ${checked} stations are under a pin or marker: ${covered.slice(0, 8).join(', ')}`);
      state.summary.push(`${label}: ${checked} stations tappable`);
    }
  } else if (view.name === 'deform') {
    const box = await page.locator(view.map).boundingBox();
    await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
    await page.waitForFunction(() => document.querySelector('[data-testid=deform-stats]')?.dataset.residue !== '');
  }

  // The controls unfolded; the schematic Metro map (its numbers fill the Advanced box).
  await setSheet(page, view.name, true);
  if (view.name === 'metro') {
    await page.click('[data-testid=mode-switch] [data-value=octilinear]');
    await page.waitForSelector(`${view.map}[data-mode=octilinear][data-transition=idle][data-layout=ready]`);
  }
  controls = Math.max(controls, await checkLayout(page, view, size, 'controls unfolded'));
  const violations = await axeViolations(page);
  check(violations.length === 0, `${label}: axe-core finds ${violations.length} serious or critical violations: ${violations.join(' | ')}`);

  // Everything unfolded: still no overlap, no number over two lines.
  await openAllDetails(page, view);
  await checkLayout(page, view, size, 'all details open');
  const numbers = await wrappedNumbers(page);
  if (screenshots) await page.screenshot({ path: join(screenshots, `phone_layout_${view.name}_${size.name}_open.png`) });
  check(numbers.checked > 0, `${label}: no number found to check`);
  check(numbers.wrapped.length === 0, `${label}: numbers broken over lines: ${numbers.wrapped.slice(0, 6).join('; ')}`);
  await closeOverlays(page, view);
  if (view.name === 'metro') state.summary.push(`${label}: ${await namesOnTheMap(page, view, label)}`);

  state.summary.push(`${label}: map ${(100 * share).toFixed(0)} %, ${controls} controls, ${numbers.checked} numbers, axe clean`);
  await context.close();
}

async function run(state) {
  const baseUrl = await serveSampleData(state, { serveArgs: ['--improve-mip', '0'] });
  const screenshots = process.env.TOURMAP_E2E_SCREENSHOTS;
  if (screenshots) mkdirSync(screenshots, { recursive: true });
  const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-gpu'] });
  try {
    for (const view of VIEWS) for (const size of SIZES) await checkView(state, browser, baseUrl, view, size, screenshots);
  } finally {
    await browser.close();
  }
  checkNoConsoleErrors(state);
}

await runTest('phone_layout', OVERALL_TIMEOUT_MS, run);
