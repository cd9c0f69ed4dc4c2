#!/usr/bin/env -S node --experimental-websocket
// WebSocket load client for the crowd stream (WS /api/v1/crowd/stream).
//
// N clients open a stream at once, send one view (scene office, 640x360, PoE 2, animation on),
// acknowledge every binary frame as the web client does ({"type":"ack","frame":id}, id = uint32 LE
// at bytes 4..7) and count frames for T seconds from their first frame. Frame latency is the
// receive time minus the frame header's timestamp (float64 LE ms since the epoch at bytes 8..15,
// taken when the server started rendering the frame). Clients over the server's stream cap get an
// error `too_many_streams` and close 1013: those are counted as refusals, not errors.
//
//   node --experimental-websocket tests/load/crowd_ws.mjs --port PORT [--clients 4] [--seconds 10]
//        [--scene office] [--width 640] [--height 360] [--poe 2] [--prepare-timeout 600] [--json]
//
// Prints frames/s per client and in total, latency p50/p99/max, errors and refusals; with --json
// one JSON object on the last line instead (tests/load/run.sh reads it). Exit 1 when no client
// got a frame.

const args = { host: "127.0.0.1", port: 0, clients: 4, seconds: 10, scene: "office", width: 640, height: 360,
  poe: 2, "prepare-timeout": 600, json: false };
for (let i = 2; i < process.argv.length; i++) {
  const k = process.argv[i].replace(/^--/, "");
  if (!(k in args)) { console.error(`unknown option ${process.argv[i]}`); process.exit(2); }
  if (typeof args[k] === "boolean") args[k] = true;
  else args[k] = typeof args[k] === "number" ? Number(process.argv[++i]) : process.argv[++i];
}
if (!args.port) { console.error("--port is required"); process.exit(2); }
if (typeof WebSocket === "undefined") {
  console.error("no global WebSocket: run with node --experimental-websocket (Node 20) or Node 22+");
  process.exit(2);
}

const url = `ws://${args.host}:${args.port}/api/v1/crowd/stream`;
const view = { type: "view", scene: args.scene, width: args.width, height: args.height, poe: args.poe, animate: true };

// One client: resolves with its counts when it ran T seconds, was refused, or failed.
function client(index) {
  return new Promise((resolve) => {
    const r = { index, frames: 0, seconds: 0, latency: [], bytes: 0, refused: false, error: null };
    let start = 0, done = false, prepareTimer = null;
    const ws = new WebSocket(url);
    ws.binaryType = "arraybuffer";
    const finish = (error) => {
      if (done) return;
      done = true;
      clearTimeout(prepareTimer);
      if (start) r.seconds = (performance.now() - start) / 1000;
      if (error && !r.refused) r.error = error;
      try { ws.close(1000); } catch { /* already closed */ }
      resolve(r);
    };
    prepareTimer = setTimeout(() => finish(`no frame within ${args["prepare-timeout"]} s`), args["prepare-timeout"] * 1000);
    ws.onopen = () => ws.send(JSON.stringify(view));
    ws.onmessage = (ev) => {
      if (typeof ev.data === "string") {
        const m = JSON.parse(ev.data);
        if (m.type === "error") {
          if (m.error?.code === "too_many_streams") r.refused = true;
          else finish(`error message: ${ev.data}`);
        }
        return;
      }
      const now = Date.now();
      const dv = new DataView(ev.data);
      const id = dv.getUint32(4, true);
      const renderedAt = dv.getFloat64(8, true);
      ws.send(JSON.stringify({ type: "ack", frame: id }));
      if (!start) {  // the first frame starts the clock (it may have waited for the scene)
        start = performance.now();
        clearTimeout(prepareTimer);
        setTimeout(() => finish(null), args.seconds * 1000);
        return;
      }
      r.frames++;
      r.bytes += ev.data.byteLength - 24;
      r.latency.push(now - renderedAt);
    };
    ws.onerror = () => { /* the close event follows with the code */ };
    ws.onclose = (ev) => {
      if (ev.code === 1013) r.refused = true;
      finish(done ? null : `closed ${ev.code} ${ev.reason || ""}`.trim());
    };
  });
}

function percentile(sorted, q) {
  return sorted.length ? sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))] : 0;
}

const results = await Promise.all(Array.from({ length: args.clients }, (_, i) => client(i)));
const streamed = results.filter((r) => r.seconds > 0 && !r.refused);
const latency = results.flatMap((r) => r.latency).sort((a, b) => a - b);
const fps = (r) => (r.seconds > 0 ? r.frames / r.seconds : 0);
const summary = {
  clients: args.clients,
  streamed: streamed.length,
  fps_total: streamed.reduce((s, r) => s + fps(r), 0),
  fps_per_client: streamed.map(fps),
  latency_ms: { p50: percentile(latency, 0.5), p99: percentile(latency, 0.99), max: latency.at(-1) ?? 0 },
  kib_per_frame: latency.length ? results.reduce((s, r) => s + r.bytes, 0) / latency.length / 1024 : 0,
  refused: results.filter((r) => r.refused).length,
  errors: results.filter((r) => r.error).map((r) => `client ${r.index}: ${r.error}`),
};

if (args.json) {
  console.log(JSON.stringify(summary));
} else {
  console.log(`crowd stream ${args.scene} ${args.width}x${args.height} PoE ${args.poe}, ${args.clients} clients, ${args.seconds} s`);
  for (const r of results) {
    const state = r.refused ? "refused (1013)" : r.error ? `error: ${r.error}` : "ok";
    console.log(`  client ${r.index}: ${fps(r).toFixed(2)} frames/s (${r.frames} frames) ${state}`);
  }
  const l = summary.latency_ms;
  console.log(`  total ${summary.fps_total.toFixed(2)} frames/s, latency p50 ${l.p50.toFixed(1)} ms, ` +
    `p99 ${l.p99.toFixed(1)} ms, max ${l.max.toFixed(1)} ms, ${summary.kib_per_frame.toFixed(1)} KiB/frame, ` +
    `${summary.errors.length} errors, ${summary.refused} refused`);
  for (const e of summary.errors) console.log(`  ${e}`);
}
process.exit(streamed.some((r) => r.frames > 0) ? 0 : 1);
