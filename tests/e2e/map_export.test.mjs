// End-to-end test of the map export (issue 14): imports the sample data into a fresh database,
// serves it with the built web client, and in headless Chromium
//  - opens Vienna's map.svg as a document: on a poster-sized page every station's name is a
//    text node (Stephansplatz and Karlsplatz among them), rendered in the labels' font with a
//    width, none overlapping another; on A3 the names are those of one of the layout's label
//    scales, and a screenshot of the page is not blank (white paper, every line's colour, dark
//    ink);
//  - uses the Metro view's download menu: its links point at the city's map files for the
//    chosen layout parameters, and the SVG link downloads the file.
//
// Run from the repository root: node tests/e2e/map_export.test.mjs
// Environment: TOURMAP_BIN (build/tourmap), TOURMAP_WEB_ROOT (build/web),
// TOURMAP_DATA_DIR (../shared/data), TOURMAP_MANIFEST (scripts/sample-data.json).

import { readFileSync } from 'node:fs';
import { inflateSync } from 'node:zlib';
import { apiJson, check, checkNoConsoleErrors, openApp, openPage, runTest, serveSampleData } from './support.mjs';

const OVERALL_TIMEOUT_MS = 150_000;
const CITY = 'vienna';
const KNOWN_NAMES = ['Stephansplatz', 'Karlsplatz'];

/** An 8-bit RGB or RGBA PNG (what Chromium's screenshots are) as { width, height, rgba(x, y) }. */
function decodePng(buffer) {
  let at = 8;
  let width = 0;
  let height = 0;
  let channels = 0;
  const idat = [];
  while (at < buffer.length) {
    const length = buffer.readUInt32BE(at);
    const type = buffer.toString('ascii', at + 4, at + 8);
    const data = buffer.subarray(at + 8, at + 8 + length);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      check(data[8] === 8 && (data[9] === 2 || data[9] === 6) && data[12] === 0, 'screenshot: not an 8-bit RGB(A) PNG');
      channels = data[9] === 6 ? 4 : 3;
    } else if (type === 'IDAT') {
      idat.push(data);
    }
    at += 12 + length;
  }
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const pixels = Buffer.alloc(height * stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; x++) {
      const a = x >= channels ? pixels[y * stride + x - channels] : 0;
      const b = y > 0 ? pixels[(y - 1) * stride + x] : 0;
      const c = x >= channels && y > 0 ? pixels[(y - 1) * stride + x - channels] : 0;
      const p = a + b - c;
      const predictor = [0, a, b, (a + b) >> 1, Math.abs(p - a) <= Math.abs(p - b) && Math.abs(p - a) <= Math.abs(p - c) ? a : Math.abs(p - b) <= Math.abs(p - c) ? b : c][filter];
      check(predictor !== undefined, `screenshot: PNG filter ${filter}`);
      pixels[y * stride + x] = (row[x] + predictor) & 0xff;
    }
  }
  return { width, height, rgb: (x, y) => [...pixels.subarray(y * stride + x * channels, y * stride + x * channels + 3)] };
}

/** The station names of an SVG document as rendered: text, width, box in the SVG's units, font. */
function renderedLabels(page) {
  return page.evaluate(() =>
    [...document.querySelectorAll('text.station-label')].map((text) => {
      const box = text.getBBox();
      return {
        // Two lines break after a space (dropped) or a hyphen (kept on the first line).
        name: [...text.querySelectorAll('tspan')]
          .map((tspan) => tspan.textContent)
          .reduce((name, line) => (name === '' ? line : name.endsWith('-') ? name + line : `${name} ${line}`), ''),
        width: text.getComputedTextLength(),
        box: { x0: box.x, y0: box.y, x1: box.x + box.width, y1: box.y + box.height },
        font: getComputedStyle(text).fontFamily,
      };
    }),
  );
}

async function openSvg(page, url) {
  const response = await page.goto(url);
  check(response?.status() === 200, `${url} answered ${response?.status()}`);
  check(response.headers()['content-type'] === 'image/svg+xml', `${url} came as ${response.headers()['content-type']}`);
}

function countOverlaps(labels) {
  // Boxes shrunk by 1 px: glyphs' side bearings may touch.
  let overlaps = 0;
  for (let i = 0; i < labels.length; i++)
    for (let j = i + 1; j < labels.length; j++) {
      const a = labels[i].box;
      const b = labels[j].box;
      if (a.x0 + 1 < b.x1 - 1 && b.x0 + 1 < a.x1 - 1 && a.y0 + 1 < b.y1 - 1 && b.y0 + 1 < a.y1 - 1) overlaps++;
    }
  return overlaps;
}

async function checkSvgDocument(page, baseUrl, state) {
  const layout = await apiJson(baseUrl, `/api/v1/cities/${CITY}/layout`);
  const stations = layout.stations.features.map((station) => station.properties.name);
  const names = new Set(stations);
  const colours = layout.lines.map((line) => line.color.toLowerCase());

  // A poster-sized page: every station is named, in the labels' font, none overlapping another.
  await openSvg(page, `${baseUrl}/api/v1/cities/${CITY}/map.svg?width=4000&height=2800`);
  let labels = await renderedLabels(page);
  const shown = new Set(labels.map((label) => label.name));
  const missing = [...names].filter((name) => !shown.has(name));
  check(missing.length === 0, `the poster does not name ${missing.length} stations: ${missing.slice(0, 5).join(', ')}`);
  const unknown = labels.filter((label) => !names.has(label.name));
  check(unknown.length === 0, `map.svg names stations the layout has not: ${unknown.slice(0, 5).map((l) => l.name).join(', ')}`);
  for (const name of KNOWN_NAMES) check(shown.has(name), `map.svg does not name ${name}`);
  const empty = labels.filter((label) => !(label.width > 0));
  check(empty.length === 0, `${empty.length} names render with no width (${empty[0]?.name})`);
  check(labels[0].font.includes('DejaVu Sans Condensed'), `names are drawn in ${labels[0].font}`);
  let overlaps = countOverlaps(labels);
  check(overlaps === 0, `${overlaps} pairs of names overlap on the poster`);
  state.summary.push(`a 4000 x 2800 map.svg names all ${names.size} stations as text, none overlapping`);

  // A3 (the default): the names of one of the server's label scales, the whole page in view.
  await page.setViewportSize({ width: 1600, height: 1140 });
  await openSvg(page, `${baseUrl}/api/v1/cities/${CITY}/map.svg`);
  labels = await renderedLabels(page);
  const a3 = labels.map((label) => label.name).sort().join('|');
  // The server improves the layout in the background (solver=auto) and the export draws the
  // layout it holds: the one fetched above, or the improved one if it landed in between.
  const after = await apiJson(baseUrl, `/api/v1/cities/${CITY}/layout`);
  const scaleOf = (answer) =>
    answer.labels.scales.findIndex((s) => s.labels.map((l) => answer.stations.features[l[0]].properties.name).sort().join('|') === a3);
  const scale = Math.max(scaleOf(layout), scaleOf(after));
  check(scale >= 0, `the A3 map's ${labels.length} names are no label scale's of the layout (before or after its improvement)`);
  overlaps = countOverlaps(labels);
  check(overlaps === 0, `${overlaps} pairs of names overlap on A3`);

  // The picture: mostly white paper, the lines' own colours, dark ink (names and title).
  const shot = decodePng(await page.screenshot());
  let white = 0;
  let ink = 0;
  const seen = new Set();
  for (let y = 0; y < shot.height; y += 2)
    for (let x = 0; x < shot.width; x += 2) {
      const [r, g, b] = shot.rgb(x, y);
      if (r > 245 && g > 245 && b > 245) white++;
      else if (r < 60 && g < 60 && b < 70) ink++;
      seen.add(((r << 16) | (g << 8) | b).toString(16).padStart(6, '0'));
    }
  const samples = Math.ceil(shot.height / 2) * Math.ceil(shot.width / 2);
  const lineColours = colours.filter((colour) => seen.has(colour));
  check(white > samples * 0.5 && white < samples * 0.98, `screenshot: ${((100 * white) / samples).toFixed(1)} % white`);
  check(ink > 500, `screenshot: ${ink} dark pixels (names, title)`);
  check(lineColours.length === colours.length, `the screenshot shows ${lineColours.length} of ${colours.length} line colours`);
  state.summary.push(
    `on A3 the ${labels.length} names of label scale ${scale}; its screenshot ${((100 * white) / samples).toFixed(0)} % paper, all ${colours.length} line colours`,
  );
  await page.setViewportSize({ width: 1280, height: 800 });
}

async function checkDownloadMenu(page, baseUrl, state) {
  await openApp(page, baseUrl, `#/metro/${CITY}`);
  await page.waitForSelector(`[data-testid=metro-map][data-status=ready][data-city="${CITY}"]`);
  const menu = page.locator('[data-testid=map-export]');
  await menu.locator('summary').click();
  // The links are filled in on the menu's toggle event, which the browser fires a task later.
  await page.waitForFunction(() => document.querySelectorAll('[data-testid=map-export] a.export-link[href]').length > 0);
  const links = await menu.locator('a.export-link').evaluateAll((anchors) =>
    anchors.map((a) => ({ format: a.dataset.format, href: a.getAttribute('href'), download: a.getAttribute('download') })),
  );
  check(links.length === 3, `the download menu offers ${links.length} files`);
  for (const link of links) {
    check(
      link.href?.startsWith(`/api/v1/cities/${CITY}/map.${link.format}?`) && link.href.includes('lengths=visual-worth') && link.href.includes('solver=auto'),
      `the ${link.format} link is ${link.href}`,
    );
    check(link.download === `${CITY}-metro-a3.${link.format}`, `the ${link.format} link saves as ${link.download}`);
  }
  const [download] = await Promise.all([page.waitForEvent('download'), menu.locator('a[data-format=svg]').click()]);
  const file = readFileSync(await download.path(), 'utf8');
  check(file.includes('<svg') && file.includes('class="station-label"'), 'the downloaded SVG is no map');
  check(download.suggestedFilename() === `${CITY}-metro-a3.svg`, `the download is named ${download.suggestedFilename()}`);
  state.summary.push(`the Metro view's menu offers SVG, PDF and PNG and downloads ${download.suggestedFilename()}`);
}

async function run(state) {
  const baseUrl = await serveSampleData(state);
  const page = await openPage(state);
  await checkSvgDocument(page, baseUrl, state);
  await checkDownloadMenu(page, baseUrl, state);
  checkNoConsoleErrors(state);
}

await runTest('map_export', OVERALL_TIMEOUT_MS, run);
