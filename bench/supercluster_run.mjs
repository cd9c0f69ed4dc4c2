// Runs mapbox/supercluster (web/node_modules, pinned 9.1.0) on the points and windows that
// build/bench/cluster_bench wrote to DIR, and writes back what cluster_bench prints beside its own
// figures. Not meant to be run by hand; cluster_bench makes and removes DIR.
//
//   node --expose-gc bench/supercluster_run.mjs DIR
//
// In DIR (all little-endian Float64, written by cluster_bench):
//   points.f64   lng, lat, worth per point (worth is unused: supercluster has no notion of it)
//   windows.f64  minLng, minLat, maxLng, maxLat per window, the exact inverse projection of
//                cluster_bench's planar windows (so they may reach past +-180 / +-90)
// Out (written here):
//   result.txt   "key value" lines: load_ms, peak_growth_mib, peak_growth_how, process_peak_mib,
//                query_p50_ms, query_p99_ms, returned_p50, then "zoom Z C" per zoom 0..16
//   zoom_Z.i32   Int32 per point: its cluster at zoom Z, numbered 0..C-1 (the partition that
//                getClusters(world, Z) shows)
//
// Query zoom: the zoom at which the window would fill a 1024-px-wide screen of 256-px tiles,
// z = floor(log2(1024 / 256 * 360 / lngSpan)) clamped to [0, 17] (17 = maxZoom + 1, the raw
// points). The bbox's longitudes are clamped to [-180, 180] before getClusters: unclamped, the
// library wraps them around the antimeridian and returns points our planar window excludes.

import fs from 'node:fs';
import path from 'node:path';
import {fileURLToPath, pathToFileURL} from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const {default: Supercluster} = await import(
  pathToFileURL(path.join(root, 'web/node_modules/supercluster/index.js')).href);

const dir = process.argv[2];
if (!dir) {
  console.error('usage: node bench/supercluster_run.mjs DIR');
  process.exit(2);
}

// Copies into an aligned buffer: small reads can come back inside a shared pool.
function readBytes(name) {
  const buf = fs.readFileSync(path.join(dir, name));
  return buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength);
}
const readF64 = name => new Float64Array(readBytes(name));

// VmHWM / VmRSS from /proc/self/status in MiB; NaN when unreadable.
function statusMiB(key) {
  try {
    const m = fs.readFileSync('/proc/self/status', 'utf8').match(new RegExp(`^${key}:\\s+(\\d+)`, 'm'));
    return m ? Number(m[1]) / 1024 : NaN;
  } catch {
    return NaN;
  }
}

function resetPeak() {
  try {
    fs.writeFileSync('/proc/self/clear_refs', '5');
    return true;
  } catch {
    return false;
  }
}

const gc = globalThis.gc ?? (() => {});
const percentile = (sorted, q) => sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];

const pts = readF64('points.f64');
const wins = readF64('windows.f64');
const n = pts.length / 3;
const features = new Array(n);
for (let i = 0; i < n; i++) {
  features[i] = {
    type: 'Feature',
    properties: {i},
    geometry: {type: 'Point', coordinates: [pts[3 * i], pts[3 * i + 1]]},
  };
}

// Warm the load path's JIT on a small prefix, then measure one full load.
new Supercluster().load(features.slice(0, Math.min(n, 10000)));
gc();
const rssBefore = statusMiB('VmRSS');
const reset = resetPeak();
const usageBefore = process.memoryUsage().rss / 1048576;
const t0 = process.hrtime.bigint();
const index = new Supercluster().load(features);
const loadMs = Number(process.hrtime.bigint() - t0) / 1e6;
const hwm = statusMiB('VmHWM');
const processPeak = process.resourceUsage().maxRSS / 1024;
const [peakGrowth, growthHow] = reset && Number.isFinite(hwm) && Number.isFinite(rssBefore) ?
  [hwm - rssBefore, 'VmHWM'] :
  [processPeak - usageBefore, 'maxRSS'];

// Queries: every window once to warm up, then every window timed.
const boxes = [];
for (let w = 0; w < wins.length / 4; w++) {
  const [x0, y0, x1, y1] = wins.subarray(4 * w, 4 * w + 4);
  const span = x1 - x0;
  const z = Math.max(0, Math.min(17, Math.floor(Math.log2(1024 / 256 * 360 / span))));
  boxes.push({bbox: [Math.max(-180, x0), y0, Math.min(180, x1), y1], z});
}
let sink = 0;
for (const b of boxes) sink += index.getClusters(b.bbox, b.z).length;
const times = [];
const returned = [];
for (const b of boxes) {
  const s = process.hrtime.bigint();
  const r = index.getClusters(b.bbox, b.z);
  times.push(Number(process.hrtime.bigint() - s) / 1e6);
  returned.push(r.length);
  sink += r.length;
}
times.sort((a, b) => a - b);
returned.sort((a, b) => a - b);

// Partitions per zoom, from the index's flat arrays (pinned 9.1.0): trees[z].data holds the
// items shown at zoom z with stride 6 (x, y, zoom, id, parent, count); an item of trees[z + 1]
// that was merged at zoom z has the merged cluster's id as parent. A point starts as item id =
// its index and follows the parents down from zoom 17 to 0.
const {trees, stride, options} = index;
const OFFSET_ID = 3, OFFSET_PARENT = 4;
const label = new Float64Array(n);  // item id of each point's cluster at the current zoom
for (let i = 0; i < n; i++) label[i] = i;
const zoomCounts = [];
let outside = 0;  // points past +-180 (synthetic jitter): no world bbox shows them
for (let i = 0; i < n; i++) if (pts[3 * i] < -180 || pts[3 * i] > 180) outside++;
for (let z = options.maxZoom; z >= 0; z--) {
  if (trees[z] !== trees[z + 1]) {
    const below = trees[z + 1];
    const parentOf = new Map();
    for (let k = 0; k < below.numItems; k++) {
      const p = below.data[k * stride + OFFSET_PARENT];
      if (p !== -1) parentOf.set(below.data[k * stride + OFFSET_ID], p);
    }
    for (let i = 0; i < n; i++) {
      const p = parentOf.get(label[i]);
      if (p !== undefined) label[i] = p;
    }
  }
  const dense = new Int32Array(n);
  const number = new Map();
  for (let i = 0; i < n; i++) {
    let c = number.get(label[i]);
    if (c === undefined) number.set(label[i], c = number.size);
    dense[i] = c;
  }
  // The partition must be the one the public API shows at this zoom.
  const shown = index.getClusters([-180, -90, 180, 90], z);
  let shownPoints = 0;
  for (const f of shown) shownPoints += f.properties.cluster ? f.properties.point_count : 1;
  if (number.size !== trees[z].numItems || shownPoints + outside < n || shownPoints > n) {
    throw new Error(`zoom ${z}: ${number.size} labels, ${trees[z].numItems} items, ` +
      `${shown.length} shown covering ${shownPoints} of ${n} points`);
  }
  fs.writeFileSync(path.join(dir, `zoom_${z}.i32`), dense);
  zoomCounts[z] = number.size;
}

// For a small set, check the mapping against getLeaves of every cluster, the slow public way.
if (n <= 20000) {
  for (const z of [0, 4, 8, 12, 16]) {
    const dense = new Int32Array(readBytes(`zoom_${z}.i32`));
    const sizes = new Map();
    for (const c of dense) sizes.set(c, (sizes.get(c) ?? 0) + 1);
    for (const f of index.getClusters([-180, -90, 180, 90], z)) {
      const members = f.properties.cluster ?
        index.getLeaves(f.properties.cluster_id, Infinity).map(l => l.properties.i) : [f.properties.i];
      for (const m of members) {
        if (dense[m] !== dense[members[0]]) throw new Error(`zoom ${z}: getLeaves disagrees for point ${m}`);
      }
      if (sizes.get(dense[members[0]]) !== members.length) throw new Error(`zoom ${z}: cluster sizes disagree`);
    }
  }
}

const lines = [
  `load_ms ${loadMs}`,
  `peak_growth_mib ${peakGrowth}`,
  `peak_growth_how ${growthHow}`,
  `process_peak_mib ${processPeak}`,
  `query_p50_ms ${percentile(times, 0.5)}`,
  `query_p99_ms ${percentile(times, 0.99)}`,
  `returned_p50 ${percentile(returned, 0.5)}`,
  ...zoomCounts.map((c, z) => `zoom ${z} ${c}`),
];
fs.writeFileSync(path.join(dir, 'result.txt'), lines.join('\n') + '\n');
if (sink < 0) console.log(sink);  // keeps the query results observable
