import type { CrowdFrameQuality, CrowdStatsMessage } from '../api/types';
import { h } from '../ui/dom';
import { formatBytes, formatCount, formatFps, formatMs, formatPoe } from './format';

/** The client's frame rate over the last frames drawn (at most 30, within 10 s: software rendering can be slow). */
class FpsMeter {
  private readonly times: number[] = [];

  tick(now: number): void {
    this.times.push(now);
    while (this.times.length > 30 || (this.times.length > 0 && now - this.times[0]! > 10000)) this.times.shift();
  }

  reset(): void {
    this.times.length = 0;
  }

  get fps(): number | undefined {
    const n = this.times.length;
    if (n < 2) return undefined;
    return ((n - 1) * 1000) / (this.times[n - 1]! - this.times[0]!);
  }
}

/** What the browser measures itself about a frame it drew. */
export interface ClientFrame {
  /** Receive time minus the header's server timestamp, ms. */
  latencyMs: number;
  width: number;
  height: number;
}

interface Row {
  term: string;
  value: string;
  key: string;
  title?: string;
  wide?: boolean;
}

/**
 * Numbers over the stream: frame rates (the browser's and the server's), triangles drawn of the
 * full-resolution total, clusters drawn, frustum-culled and occluded, server milliseconds per
 * stage, bytes per frame and the frame latency. A <details>, folded until opened: it would cover the picture.
 *
 * For tests the element reports data-frame, data-scene, data-mode, data-poe, data-triangles, data-width,
 * data-height and data-latency-ms of the last stats shown.
 */
export class StatsOverlay {
  readonly element: HTMLElement;
  private readonly table: HTMLDListElement;
  private readonly meter = new FpsMeter();
  private stats?: CrowdStatsMessage;
  private client?: ClientFrame;
  /** Full-resolution triangles of the scene (the server's total). */
  private fullTriangles?: number | null;
  private dropped = 0;

  constructor() {
    this.table = h('dl', { class: 'stats-table' });
    this.element = h(
      'details',
      { class: 'stats crowd-stats', 'data-testid': 'crowd-stats', 'aria-label': 'Rendering statistics' },
      h('summary', {}, 'Numbers'),
      this.table,
    );
    this.clear();
  }

  clear(text = 'No frame yet.'): void {
    this.stats = undefined;
    this.client = undefined;
    this.meter.reset();
    this.table.replaceChildren(h('div', { class: 'wide' }, h('dt', {}, text)));
    for (const key of ['frame', 'scene', 'mode', 'poe', 'triangles', 'width', 'height', 'latencyMs']) delete this.element.dataset[key];
  }

  setFullTriangles(triangles: number | null | undefined): void {
    this.fullTriangles = triangles;
  }

  /** A frame was drawn. */
  frameDrawn(frame: ClientFrame, dropped: number): void {
    this.meter.tick(performance.now());
    this.client = frame;
    this.dropped = dropped;
    this.element.dataset.latencyMs = frame.latencyMs.toFixed(1);
    this.render();
  }

  /** The server's numbers for its latest frame. */
  show(stats: CrowdStatsMessage): void {
    this.stats = stats;
    const data = this.element.dataset;
    data.frame = String(stats.frame);
    data.scene = stats.scene;
    data.mode = stats.mode;
    data.poe = String(stats.poe);
    data.triangles = String(stats.triangles);
    data.width = String(stats.width);
    data.height = String(stats.height);
    data.quality = stats.quality?.mode ?? 'still';
    data.qualityLevel = String(stats.quality?.level ?? 0);
    this.render();
  }

  private render(): void {
    const { stats, client } = this;
    if (!stats && !client) return;
    const full = stats?.full_triangles ?? this.fullTriangles;
    const share = stats && full ? ` (${((100 * stats.triangles) / full).toPrecision(2)}%)` : '';
    const rows: Row[] = [
      { term: 'FPS', value: formatFps(this.meter.fps), key: 'fps', title: 'Browser: frames drawn per second' },
      { term: 'Server FPS', value: formatFps(stats?.fps), key: 'server-fps', title: 'Server: frames rendered per second' },
      {
        term: 'Triangles',
        value: `${formatCount(stats?.triangles)}${share}`,
        key: 'triangles',
        title: 'Triangles drawn, and their share of the full-resolution crowd',
        wide: true,
      },
      { term: 'Clusters', value: formatCount(stats?.clusters.drawn), key: 'clusters-drawn', title: 'Clusters drawn' },
      { term: 'Culled', value: formatCount(stats?.clusters.frustum_culled), key: 'clusters-culled', title: 'Clusters outside the view (frustum-culled)' },
      { term: 'Occluded', value: formatCount(stats?.clusters.occluded), key: 'clusters-occluded', title: 'Clusters hidden behind others (occlusion-culled)' },
      { term: 'Characters', value: formatCount(stats?.characters), key: 'characters' },
      { term: 'LOD cut', value: formatMs(stats?.ms.lod_cut), key: 'ms-lod-cut', title: 'Server: choosing the clusters to draw' },
      { term: 'Render', value: formatMs(stats?.ms.render), key: 'ms-render', title: 'Server: drawing the frame' },
      ...(stats?.ms.readback !== undefined
        ? [{ term: 'Readback', value: formatMs(stats.ms.readback), key: 'ms-readback', title: 'Server: copying the picture off the GPU' }]
        : []),
      { term: 'Encode', value: formatMs(stats?.ms.encode), key: 'ms-encode', title: 'Server: JPEG encoding' },
      { term: 'Frame', value: formatMs(stats?.ms.frame), key: 'ms-frame', title: 'Server: the whole frame' },
      { term: 'Bytes', value: formatBytes(stats?.bytes), key: 'bytes', title: 'JPEG bytes of the frame' },
      {
        term: 'Latency',
        value: formatMs(client?.latencyMs),
        key: 'latency',
        title: 'Time from the server stamping the frame to the browser receiving it (the two clocks may differ)',
      },
      { term: 'Size', value: stats ? `${stats.width} × ${stats.height}` : client ? `${client.width} × ${client.height}` : '—', key: 'size' },
      { term: 'Skipped', value: formatCount(this.dropped), key: 'dropped', title: 'Frames the browser skipped because a newer one arrived while decoding' },
      { term: 'Mode', value: stats ? `${stats.mode} · PoE ${formatPoe(stats.poe)} px` : '—', key: 'mode', wide: true },
      {
        term: 'Quality',
        value: stats?.quality ? qualityText(stats.quality) : '—',
        key: 'quality',
        title: 'While moving, frames are drawn smaller and simpler to keep the frame rate; at rest, at full quality',
        wide: true,
      },
    ];
    this.table.replaceChildren(
      ...rows.map(({ term, value, key, title, wide }) =>
        h('div', { class: wide ? 'wide' : undefined, 'data-stat': key, title }, h('dt', {}, term), h('dd', {}, value)),
      ),
    );
  }
}

/** "moving · 70 % size · PoE 1 px" or "still · full". */
function qualityText(q: CrowdFrameQuality): string {
  if (q.level === 0) return `${q.mode === 'interactive' ? 'moving' : 'still'} · full`;
  return `moving · ${Math.round(q.scale * 100)}\u00a0% size · PoE ${formatPoe(q.poe)}\u00a0px`;
}
