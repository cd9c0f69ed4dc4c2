import type { ClusterSpace, ClustersResponse, PoiCluster } from '../api/types';
import { LABEL_FONT, labelWidth, type Box } from '../map/labels';
import { svg } from '../map/svg';
import type { Anchor, SvgMap } from '../map/svg-map';
import { MapTooltip } from '../map/tooltip';
import type { MapObstacles, MapSegment } from './metro-layers';
import type { Pt } from './morph';
import { httpUrl } from '../ui/url';

export interface ClusterPick {
  cluster: PoiCluster;
  /** Where the marker stands (its representative POI), in frame units. */
  point: Pt;
  /** The cluster's centre, in frame units. */
  center: Pt;
  preview: boolean;
}

/** A thumbnail's radius, and the pin's head centre above the point. */
const THUMB_RADIUS = 19;
const THUMB_Y = -30;
const HEAD_RADIUS = 11;
const HEAD_Y = -19;
const PREVIEW_RADIUS = 4;
const NAME_MAX = 30;

let clipIds = 0;

/**
 * Where a marker may stand instead of on its place: its place, then rings of 8 spots, upwards
 * first, out to where a leader line still reads as pointing at the place (a dense centre,
 * London's seen whole, is 400 px across: the outer rings reach past it).
 */
const OFFSETS: [number, number][] = [[0, 0]];
for (const radius of [26, 44, 64, 90, 120, 160, 210, 270]) {
  for (const degrees of [270, 315, 225, 0, 180, 45, 135, 90]) {
    const a = (degrees * Math.PI) / 180;
    OFFSETS.push([Math.round(radius * Math.cos(a)), Math.round(radius * Math.sin(a))]);
  }
}

/** Does the segment (with its half width) come into the box? */
function segmentMeets(s: MapSegment, box: Box): boolean {
  const grown = { x0: box.x0 - s.half, y0: box.y0 - s.half, x1: box.x1 + s.half, y1: box.y1 + s.half };
  if (Math.max(s.x0, s.x1) < grown.x0 || Math.min(s.x0, s.x1) > grown.x1 || Math.max(s.y0, s.y1) < grown.y0 || Math.min(s.y0, s.y1) > grown.y1) return false;
  // Liang-Barsky clipping against the grown box.
  let t0 = 0;
  let t1 = 1;
  const dx = s.x1 - s.x0;
  const dy = s.y1 - s.y0;
  const p = [-dx, dx, -dy, dy];
  const q = [s.x0 - grown.x0, grown.x1 - s.x0, s.y0 - grown.y0, grown.y1 - s.y0];
  for (let i = 0; i < 4; i++) {
    if (p[i] === 0) {
      if (q[i]! < 0) return false;
      continue;
    }
    const t = q[i]! / p[i]!;
    if (p[i]! < 0) t0 = Math.max(t0, t);
    else t1 = Math.min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

const shorten = (text: string) => (text.length > NAME_MAX ? `${text.slice(0, NAME_MAX - 1).trimEnd()}…` : text);

interface Marker {
  pick: ClusterPick;
  element: SVGGElement;
  anchor: Anchor;
  /** From the marker's stem back to its place, when it had to move off the map's features. */
  leader?: SVGPathElement;
  /** Offsets of the marker's box from the point, in pixels. */
  box: Box;
  /** The representative's name, right of the pin or else left of it; `box` is where it is now. */
  name?: { text: SVGTextElement; right: Box; left: Box; box: Box };
}

/**
 * The active POI clusters of the window: the top ones as markers standing on their
 * representative POI (its photo in a round frame, or a pin with the cluster's size and the
 * POI's name), the previews as small dots. The layer reports what it shows in data-cluster-ids
 * (markers, by prominence), data-preview-ids and data-space.
 */
export class ClusterLayer {
  private markers: Marker[] = [];
  private readonly clipId = `cluster-thumb-${++clipIds}`;
  private readonly tooltip: MapTooltip;
  private readonly listeners = new AbortController();
  private readonly stopRender: () => void;
  private readonly stopSettle: () => void;
  private obstacles: () => MapObstacles = () => ({ boxes: [], segments: [] });

  constructor(
    private readonly map: SvgMap,
    private readonly layer: SVGGElement,
    private readonly onPick: (pick: ClusterPick) => void,
    /** Called after the markers changed (station names make way for them). */
    private readonly onChange: () => void,
  ) {
    layer.dataset.testid = 'cluster-layer';
    const defs = svg('defs');
    const clip = svg('clipPath', { id: this.clipId, clipPathUnits: 'userSpaceOnUse' });
    clip.append(svg('circle', { cx: 0, cy: THUMB_Y, r: THUMB_RADIUS - 2 }));
    defs.append(clip);
    layer.append(defs);
    this.tooltip = new MapTooltip(map.element);
    this.listen();
    this.stopRender = map.onRender(() => this.hideCrowdedNames());
    this.stopSettle = map.onSettle(() => this.arrange());
    this.clear();
  }

  /** What markers move off: station symbols, names and lines (asked at every arrangement). */
  setObstacles(obstacles: () => MapObstacles): void {
    this.obstacles = obstacles;
  }

  /**
   * Shows an answer of /clusters; `toFrame` puts its positions (lon/lat or layout metres) on the
   * map, `representativeAt` may say better where a representative is (in the same units).
   */
  show(
    answer: ClustersResponse,
    space: ClusterSpace,
    toFrame: (position: [number, number]) => Pt,
    representativeAt: (cluster: PoiCluster) => [number, number] | undefined = () => undefined,
  ): void {
    this.removeMarkers();
    const place = (cluster: PoiCluster) => ({
      point: toFrame(representativeAt(cluster) ?? cluster.representative.position),
      center: toFrame(cluster.center),
    });
    const previews = answer.previews.map((cluster) => this.drawPreview(cluster, place(cluster)));
    // Least prominent first, so the most prominent is drawn on top.
    const top = answer.clusters.map((cluster) => this.drawMarker(cluster, place(cluster)));
    for (const marker of [...top].reverse()) this.layer.append(marker.element);
    this.markers = [...previews, ...top];
    this.layer.dataset.space = space;
    this.layer.dataset.clusterIds = answer.clusters.map((cluster) => cluster.id).join(' ');
    this.layer.dataset.previewIds = answer.previews.map((cluster) => cluster.id).join(' ');
    this.layer.dataset.active = String(answer.active);
    this.arrange();
    this.onChange();
  }

  clear(): void {
    this.removeMarkers();
    this.layer.dataset.clusterIds = '';
    this.layer.dataset.previewIds = '';
    this.layer.dataset.active = '0';
    delete this.layer.dataset.space;
    this.onChange();
  }

  /** Screen boxes of the markers and their names, for station names to keep clear of. */
  boxes(): Box[] {
    if (this.layer.style.display === 'none') return [];
    const out: Box[] = [];
    for (const marker of this.markers) {
      const [px, py] = this.map.toScreen(marker.anchor.x, marker.anchor.y);
      const [x, y] = [px + marker.anchor.dx, py + marker.anchor.dy];
      const shift = (box: Box): Box => ({ x0: x + box.x0, y0: y + box.y0, x1: x + box.x1, y1: y + box.y1 });
      out.push(shift(marker.box));
      if (marker.name && marker.name.text.getAttribute('visibility') !== 'hidden') out.push(shift(marker.name.box));
    }
    return out;
  }

  destroy(): void {
    this.listeners.abort();
    this.stopRender();
    this.stopSettle();
    this.tooltip.destroy();
    this.removeMarkers();
  }

  private removeMarkers(): void {
    this.map.removeAnchors(this.markers.map((marker) => marker.anchor));
    for (const marker of this.markers) marker.element.remove();
    this.markers = [];
    this.tooltip.hide();
  }

  private drawPreview(cluster: PoiCluster, { point, center }: { point: Pt; center: Pt }): Marker {
    const element = svg('g', { class: 'cluster cluster-preview', 'data-id': cluster.id, 'data-size': cluster.size });
    element.append(svg('circle', { r: PREVIEW_RADIUS }));
    this.layer.append(element);
    const r = PREVIEW_RADIUS + 1;
    return { pick: { cluster, point, center, preview: true }, element, anchor: this.map.anchor(element, point), box: { x0: -r, y0: -r, x1: r, y1: r } };
  }

  private drawMarker(cluster: PoiCluster, { point, center }: { point: Pt; center: Pt }): Marker {
    const { representative, size } = cluster;
    const image = httpUrl(representative.image);
    const element = svg('g', {
      class: `cluster cluster-marker ${image ? 'with-image' : 'with-name'}`,
      'data-id': cluster.id,
      'data-size': size,
      'data-representative': representative.id,
      role: 'button',
      'aria-label': `${representative.name}${size > 1 ? `, and ${size - 1} more places` : ''}`,
    });
    const marker: Marker = { pick: { cluster, point, center, preview: false }, element, anchor: this.map.anchor(element, point), box: { x0: 0, y0: 0, x1: 0, y1: 0 } };
    if (image) this.drawThumbnail(marker, image);
    else this.drawPin(marker);
    return marker;
  }

  /**
   * Moves each marker (by prominence) off station symbols, station names, lines and the
   * markers placed before it: to the nearest free spot on rings around its place, joined to it
   * by a leader line. Where no spot is free, to the one that covers the least: never another
   * marker, the map's edge or a panel over the map where avoidable, then as few stations and names, then as few
   * lines as can be (on its place, a cluster in London's centre hid four interchanges). Then
   * names the markers.
   */
  private arrange(): void {
    const top = this.markers.filter((marker) => !marker.pick.preview);
    if (top.length === 0) return;
    const { boxes, segments, covered = [] } = this.obstacles();
    const { width, height } = this.map.size;
    const taken: Box[] = [];
    const overlaps = (a: Box, b: Box) => a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
    const count = <T>(items: T[], hits: (item: T) => boolean) => items.reduce((n, item) => n + (hits(item) ? 1 : 0), 0);
    const outside = (box: Box) => box.x0 < 0 || box.y0 < 0 || box.x1 > width || box.y1 > height || covered.some((b) => overlaps(box, b));
    // What a marker at `box` covers, worst first in the weights; 0: a free spot.
    const cost = (box: Box) =>
      1e6 * count(taken, (b) => overlaps(box, b)) +
      1e4 * (outside(box) ? 1 : 0) +
      100 * count(boxes, (b) => overlaps(box, b)) +
      count(segments, (segment) => segmentMeets(segment, box));
    // Most prominent first: it keeps its place if it can.
    for (const marker of [...top].reverse()) {
      const [x, y] = this.map.toScreen(marker.anchor.x, marker.anchor.y);
      const at = (dx: number, dy: number): Box => ({ x0: x + dx + marker.box.x0, y0: y + dy + marker.box.y0, x1: x + dx + marker.box.x1, y1: y + dy + marker.box.y1 });
      let offset = OFFSETS[0]!;
      let least = Infinity;
      for (const [dx, dy] of OFFSETS) {
        const c = cost(at(dx, dy));
        if (c < least) [offset, least] = [[dx, dy], c];
        if (c === 0) break;
      }
      this.setOffset(marker, offset[0], offset[1]);
      taken.push(at(offset[0], offset[1]));
    }
    this.hideCrowdedNames(taken, boxes, segments, covered);
  }

  private setOffset(marker: Marker, dx: number, dy: number): void {
    marker.anchor.dx = dx;
    marker.anchor.dy = dy;
    if (dx === 0 && dy === 0) {
      marker.leader?.remove();
      marker.leader = undefined;
    } else {
      marker.leader ??= svg('path', { class: 'cluster-leader' });
      marker.element.prepend(marker.leader);
      marker.leader.setAttribute('d', `M${-dx} ${-dy}L0 0M${-dx} ${-dy}m-2 0a2 2 0 1 0 4 0a2 2 0 1 0 -4 0`);
    }
    this.map.requestRender();
  }

  /** A round photo on a short stem, with the cluster's size on a badge. */
  private drawThumbnail(marker: Marker, href: string): void {
    const { element, pick } = marker;
    element.append(
      svg('path', { class: 'cluster-stem', d: `M0 0L-5 ${THUMB_Y + THUMB_RADIUS - 3}L5 ${THUMB_Y + THUMB_RADIUS - 3}Z` }),
      svg('circle', { class: 'cluster-frame', cy: THUMB_Y, r: THUMB_RADIUS }),
    );
    const photo = svg('image', {
      href,
      x: -THUMB_RADIUS,
      y: THUMB_Y - THUMB_RADIUS,
      width: 2 * THUMB_RADIUS,
      height: 2 * THUMB_RADIUS,
      preserveAspectRatio: 'xMidYMid slice',
      'clip-path': `url(#${this.clipId})`,
    });
    // A photo that cannot be loaded turns the marker into a named pin.
    photo.addEventListener('error', () => {
      element.replaceChildren();
      element.classList.replace('with-image', 'with-name');
      this.drawPin(marker);
      // A pin takes less room than the photo: the markers are arranged again.
      this.arrange();
      this.onChange();
    });
    element.append(photo);
    if (pick.cluster.size > 1) {
      const badge = svg('g', { class: 'cluster-badge', transform: `translate(${THUMB_RADIUS - 3},${THUMB_Y - THUMB_RADIUS + 3})` });
      const text = svg('text', { 'text-anchor': 'middle', dy: 4 });
      text.textContent = String(pick.cluster.size);
      badge.append(svg('circle', { r: 9 }), text);
      // The label starts with the badge's number (WCAG 2.5.3, label in name).
      element.setAttribute('aria-label', `${pick.cluster.size} places: ${pick.cluster.representative.name} and ${pick.cluster.size - 1} more`);
      element.append(badge);
    }
    marker.box = { x0: -THUMB_RADIUS, y0: THUMB_Y - THUMB_RADIUS - 6, x1: THUMB_RADIUS + 6, y1: 2 };
  }

  /** A pin with the cluster's size in its head and the representative's name beside it. */
  private drawPin(marker: Marker): void {
    const { element, pick } = marker;
    const size = pick.cluster.size;
    element.append(
      svg('path', { class: 'cluster-stem', d: `M0 0L-4 ${HEAD_Y + HEAD_RADIUS - 3}L4 ${HEAD_Y + HEAD_RADIUS - 3}Z` }),
      svg('circle', { class: 'cluster-head', cy: HEAD_Y, r: HEAD_RADIUS }),
    );
    // A single place: a dot in the head (a count of 1 reads as a cluster of one).
    const count =
      size > 1
        ? Object.assign(svg('text', { class: 'cluster-count', 'text-anchor': 'middle', y: HEAD_Y, dy: 4 }), { textContent: String(size) })
        : svg('circle', { class: 'cluster-dot', cy: HEAD_Y, r: 3.5 });
    const name = svg('text', { class: 'cluster-name', x: HEAD_RADIUS + 4, y: HEAD_Y, dy: 4 });
    name.style.font = LABEL_FONT;
    const label = shorten(pick.cluster.representative.name);
    // A leading space (not drawn: SVG drops it) keeps count and name apart in the text a screen
    // reader reads, and the aria-label starts with that text (WCAG 2.5.3, label in name).
    name.textContent = size > 1 ? ` ${label}` : label;
    const full = pick.cluster.representative.name;
    element.setAttribute(
      'aria-label',
      size > 1 ? `${size} ${label}: ${full} and ${size - 1} more places` : label === full ? full : `${label} ${full}`,
    );
    element.append(count, name);
    const width = labelWidth(label);
    marker.box = { x0: -HEAD_RADIUS, y0: HEAD_Y - HEAD_RADIUS, x1: HEAD_RADIUS, y1: 2 };
    const right = { x0: HEAD_RADIUS + 2, y0: HEAD_Y - 9, x1: HEAD_RADIUS + 6 + width, y1: HEAD_Y + 9 };
    const left = { x0: -HEAD_RADIUS - 6 - width, y0: HEAD_Y - 9, x1: -HEAD_RADIUS - 2, y1: HEAD_Y + 9 };
    marker.name = { text: name, right, left, box: right };
  }

  /**
   * Names go right of their pin, or left, where they cover no marker, no name placed before
   * (by prominence) and nothing in `boxes` or on `segments` (the map's features), within the
   * map and off the panels over it (`covered`); a name with room on neither side is hidden.
   */
  private hideCrowdedNames(markerBoxes?: Box[], boxes: Box[] = [], segments: MapSegment[] = [], covered: Box[] = []): void {
    const overlaps = (a: Box, b: Box) => a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
    const top = this.markers.filter((marker) => !marker.pick.preview);
    const placed = top.map((marker) => {
      const [x, y] = this.map.toScreen(marker.anchor.x, marker.anchor.y);
      const [ox, oy] = [x + marker.anchor.dx, y + marker.anchor.dy];
      const shift = (box: Box): Box => ({ x0: ox + box.x0, y0: oy + box.y0, x1: ox + box.x1, y1: oy + box.y1 });
      return { marker, box: shift(marker.box), shift };
    });
    // Only when arranged (on settling) do names look at the map's features; while panning the
    // sides found then stay.
    if (!markerBoxes) return;
    const taken: Box[] = placed.map(({ box }) => box);
    const { width, height } = this.map.size;
    const shown = (b: Box) => b.x0 >= 0 && b.y0 >= 0 && b.x1 <= width && b.y1 <= height && !covered.some((c) => overlaps(b, c));
    for (const { marker, box, shift } of placed) {
      const name = marker.name;
      if (!name) continue;
      const side = [name.right, name.left].find((candidate) => {
        const screen = shift(candidate);
        return (
          shown(screen) &&
          !taken.some((other) => other !== box && overlaps(screen, other)) &&
          !boxes.some((other) => overlaps(screen, other)) &&
          !segments.some((segment) => segmentMeets(segment, screen))
        );
      });
      name.text.setAttribute('visibility', side ? 'visible' : 'hidden');
      if (!side) continue;
      name.box = side;
      const onLeft = side === name.left;
      name.text.setAttribute('x', String(onLeft ? -HEAD_RADIUS - 4 : HEAD_RADIUS + 4));
      name.text.setAttribute('text-anchor', onLeft ? 'end' : 'start');
      taken.push(shift(side));
    }
  }

  private markerAt(target: EventTarget | null): Marker | undefined {
    const element = target instanceof Element ? target.closest('.cluster') : null;
    return element ? this.markers.find((marker) => marker.element === element) : undefined;
  }

  private listen(): void {
    const options = { signal: this.listeners.signal };
    this.layer.addEventListener(
      'click',
      (event) => {
        const marker = this.markerAt(event.target);
        if (marker) this.onPick(marker.pick);
      },
      options,
    );
    this.layer.addEventListener(
      'pointerover',
      (event) => {
        const marker = this.markerAt(event.target);
        if (!marker || event.pointerType !== 'mouse') return;
        const { cluster } = marker.pick;
        const more = cluster.size > 1 ? ` · ${cluster.size} places` : '';
        const [x, y] = this.map.toScreen(marker.anchor.x, marker.anchor.y);
        this.tooltip.show(`${cluster.representative.name}${more}`, [x, y + (marker.pick.preview ? 0 : marker.box.y0 + 6)]);
      },
      options,
    );
    this.layer.addEventListener('pointerout', () => this.tooltip.hide(), options);
    this.layer.addEventListener('pointerdown', () => this.tooltip.hide(), options);
  }
}
