import type { PoiFeature } from '../api/types';
import { fetchWalk, walkErrorText, type StationWalk, type WalkResponse } from '../api/walk';
import { formatDistance } from '../map/distance';
import type { Frame } from '../map/projection';
import { polylinePath, svg } from '../map/svg';
import type { SvgMap } from '../map/svg-map';
import '../styles/interests-walk.css';
import { h } from '../ui/dom';
import { LatestRequest } from './latest-request';
import type { Placement } from './layout-geometry';
import type { Geometry, Pt } from './morph';

/** What the view draws now, for placing a walk on it. */
export interface WalkDrawing {
  /** The drawing shown; null while the map morphs (the walk is hidden meanwhile). */
  mode: 'geographic' | 'octilinear' | null;
  frame?: Frame;
  /** The schematic drawn (octilinear mode): where its layout frame goes on the map. */
  placement?: Placement;
  /** Where stations and POIs are drawn now (frame units). */
  geometry?: Geometry;
}

/** A walk shown is zoomed to take at most this share of the map left free by the details. */
const FOCUS_SHARE = 0.6;
/** ... but the map zooms in at most this much for it (and never out). */
const FOCUS_MAX_ZOOM = 8;

/** "7 min walk (550 m)". */
export function walkText(walk: StationWalk): string {
  return `${Math.max(1, Math.round(walk.minutes))}\u00a0min walk (${formatDistance(walk.distance_m)})`;
}

/**
 * Moves a path so it starts at `start` and ends at `end`, each point by the blend of the two
 * ends' offsets by its share of the path's length. The server's `path_layout` is in the
 * default layout's frame; a schematic with other parameters (interests, uniform lengths) puts
 * the POI and the station a little elsewhere, and the path follows them. For the default
 * layout and for the geographic map the offsets are (nearly) zero.
 */
export function pinEnds(points: Pt[], start: Pt | undefined, end: Pt | undefined): Pt[] {
  if (points.length === 0 || !start || !end) return points;
  const first = points[0]!;
  const last = points[points.length - 1]!;
  const d0: Pt = [start[0] - first[0], start[1] - first[1]];
  const d1: Pt = [end[0] - last[0], end[1] - last[1]];
  const along = [0];
  for (let i = 1; i < points.length; i++) {
    along.push(along[i - 1]! + Math.hypot(points[i]![0] - points[i - 1]![0], points[i]![1] - points[i - 1]![1]));
  }
  const total = along[along.length - 1]!;
  return points.map(([x, y], i) => {
    const s = total > 0 ? along[i]! / total : i / Math.max(1, points.length - 1);
    return [x + (1 - s) * d0[0] + s * d1[0], y + (1 - s) * d0[1] + s * d1[1]];
  });
}

/**
 * "Walk from the nearest station": the button in a POI's details, the answer in words, and the
 * walks drawn over the map (the nearest prominent, the others faint) in the geographic map
 * (`path` projected as the stations are) and in the schematic (`path_layout` placed as the
 * layout is). One walk at a time: clear() drops it (another pick, the panel closed, another
 * city). The layer reports data-status (loading, ready, error), data-mode (the drawing the
 * paths are drawn for, or hidden) and data-walks (paths drawn) for tests.
 */
export class WalkControl {
  private layer?: SVGGElement;
  private cityId?: string;
  private hasRoads = false;
  private answer?: WalkResponse;
  /** The walk drawn prominent (an index into answer.walks). */
  private chosen = 0;
  private readonly request = new LatestRequest<WalkResponse>();
  /** The walks' points drawn (frame units), for focus(). */
  private drawnPoints: Pt[] = [];
  /** The drawing the walk was last drawn on, and the details panel it is shown in. */
  private drawnMode: WalkDrawing['mode'] = null;
  private panelElement: Element | null = null;

  constructor(
    private readonly map: SvgMap,
    private readonly drawing: () => WalkDrawing,
  ) {}

  /** A new city drawn: its layer (above the lines, under the markers) and whether it has roads. */
  setCity(cityId: string | undefined, hasRoads: boolean): void {
    this.clear();
    this.cityId = cityId;
    this.hasRoads = hasRoads;
    this.layer = cityId ? this.map.addLayer('walk', 'world') : undefined;
  }

  /** The details' walk section for `poi`, or null when the city has no road network. */
  panel(poi: PoiFeature): HTMLElement | null {
    const cityId = this.cityId;
    if (!cityId || !this.hasRoads) return null;
    const button = h('button', { type: 'button', class: 'button walk-button', 'data-testid': 'walk-button' }, 'Walk from the nearest station');
    const result = h('div', { class: 'walk-result', 'aria-live': 'polite', 'data-testid': 'walk-result' });
    const section = h('section', { class: 'walk' }, button, result);
    button.addEventListener('click', () => this.ask(cityId, poi, button, result));
    return section;
  }

  private ask(cityId: string, poi: PoiFeature, button: HTMLButtonElement, result: HTMLElement): void {
    this.removePaths();
    this.answer = undefined;
    button.disabled = true;
    result.replaceChildren(h('p', { class: 'walk-waiting' }, 'Finding the walk…'));
    if (this.layer) this.layer.dataset.status = 'loading';
    this.request.run(
      (signal) => fetchWalk(cityId, poi.properties.id, signal),
      (answer) => {
        button.disabled = false;
        if (this.cityId !== cityId) return;
        this.answer = answer;
        this.chosen = 0;
        this.describe(answer, result);
        if (this.layer) this.layer.dataset.status = 'ready';
        this.panelElement = result.closest('.details-panel');
        this.redraw();
        this.focus(false);
      },
      (error) => {
        button.disabled = false;
        result.replaceChildren(h('p', { class: 'walk-error' }, walkErrorText(error)));
        if (this.layer) this.layer.dataset.status = 'error';
      },
    );
  }

  private describe(answer: WalkResponse, result: HTMLElement): void {
    if (answer.walks.length === 0) {
      const text =
        answer.poi.road_m === null
          ? 'This place is too far from any street to plan a walk.'
          : `No station is within a ${formatDistance(answer.params.max_m)} walk of this place.`;
      result.replaceChildren(h('p', { class: 'walk-none' }, text));
      return;
    }
    const items = answer.walks.map((walk, i) => {
      const item = h(
        'button',
        { type: 'button', class: 'walk-item', 'aria-pressed': String(i === this.chosen), 'data-station': walk.station.id },
        h('span', { class: 'walk-station' }, walk.station.name),
        h('span', { class: 'walk-time' }, ` · ${walkText(walk)}`),
      );
      item.addEventListener('click', () => {
        this.chosen = i;
        for (const [j, other] of [...result.querySelectorAll('.walk-item')].entries()) other.setAttribute('aria-pressed', String(j === i));
        this.redraw();
      });
      return h('li', {}, item);
    });
    const list = h('ul', { class: 'walk-list' }, ...items);
    if (answer.walks.length > 1) result.replaceChildren(list, h('p', { class: 'walk-more' }, 'Tap another station to show its walk.'));
    else result.replaceChildren(list);
  }

  /** Draws the walk for what the map shows now (hidden while it morphs). */
  redraw(): void {
    const layer = this.layer;
    const answer = this.answer;
    if (!layer) return;
    this.removePaths();
    const { mode, frame, placement, geometry } = this.drawing();
    if (!answer || answer.walks.length === 0 || !mode || !frame || !geometry) {
      layer.dataset.mode = answer && !mode ? 'hidden' : 'none';
      layer.dataset.walks = '0';
      return;
    }
    const start = geometry.pois.get(answer.poi.id);
    let drawn = 0;
    // The chosen walk last: on top of the faint ones.
    const order = answer.walks.map((walk, i) => ({ walk, i })).sort((a, b) => Number(a.i === this.chosen) - Number(b.i === this.chosen));
    for (const { walk, i } of order) {
      let base: Pt[] | null = null;
      if (mode === 'geographic') base = walk.path.map((p) => frame.project(p));
      else if (placement && walk.path_layout) base = walk.path_layout.map((p) => placement.toFrame(p));
      if (!base || base.length < 2) continue;
      const points = pinEnds(base, start, geometry.stations.get(walk.station.id));
      this.drawnPoints.push(...points);
      const d = polylinePath(points);
      const prominent = i === this.chosen;
      const kind = prominent ? 'walk-path walk-nearest' : 'walk-path walk-other';
      layer.append(
        svg('path', { class: `${kind} walk-casing`, d }),
        svg('path', { class: `${kind} walk-line`, d, 'data-station': walk.station.id }),
      );
      drawn++;
    }
    layer.dataset.mode = mode;
    layer.dataset.walks = String(drawn);
    // The other drawing puts the walk elsewhere: brought back into view if it left it.
    const switched = this.drawnMode !== null && this.drawnMode !== mode;
    this.drawnMode = mode;
    if (switched) this.focus(true);
  }

  /**
   * Zooms and pans so the walks drawn fill a good part of the map beside (desktop) or above
   * (phone) the details panel (`onlyIfOut`: only when part of it is out of that area): a walk of a few hundred metres is a few pixels in a
   * whole city. Never zooms out; an animated move, so the map settles (clusters) after it.
   */
  private focus(onlyIfOut: boolean): void {
    const covering = this.panelElement;
    const points = this.drawnPoints;
    const { width, height } = this.map.size;
    if (points.length < 2 || width === 0 || height === 0) return;
    const area = this.map.element.getBoundingClientRect();
    const free = { x0: 0, y0: 0, x1: width, y1: height };
    const panel = covering?.getBoundingClientRect();
    if (panel && panel.width > 0) {
      const left = panel.left - area.left;
      const top = panel.top - area.top;
      if (left > width / 2) free.x1 = left;
      else if (top > height / 4) free.y1 = top;
    }
    if (onlyIfOut) {
      const inside = points.every((p) => {
        const [sx, sy] = this.map.toScreen(...p);
        return sx >= free.x0 && sx <= free.x1 && sy >= free.y0 && sy <= free.y1;
      });
      if (inside) return;
    }
    const xs = points.map(([x]) => x);
    const ys = points.map(([, y]) => y);
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const k0 = this.map.view.k;
    const fit = FOCUS_SHARE * Math.min((free.x1 - free.x0) / Math.max(x1 - x0, 1e-9), (free.y1 - free.y0) / Math.max(y1 - y0, 1e-9));
    const k = Math.min(Math.max(k0, fit), k0 * FOCUS_MAX_ZOOM);
    // zoomTo puts a point at the map's centre: the one that brings the walks' centre to the free area's.
    const centre: Pt = [(x0 + x1) / 2, (y0 + y1) / 2];
    const target: Pt = [(free.x0 + free.x1) / 2, (free.y0 + free.y1) / 2];
    const [sx, sy] = this.map.toScreen(...centre);
    if (k === k0 && Math.abs(sx - target[0]) < (free.x1 - free.x0) / 4 && Math.abs(sy - target[1]) < (free.y1 - free.y0) / 4) return;
    this.map.zoomTo(centre[0] - (target[0] - width / 2) / k, centre[1] - (target[1] - height / 2) / k, k / k0);
  }

  /** Forgets the walk: nothing drawn, nothing asked for. */
  clear(): void {
    this.request.cancel();
    this.answer = undefined;
    this.drawnMode = null;
    this.panelElement = null;
    this.removePaths();
    if (this.layer) {
      delete this.layer.dataset.status;
      delete this.layer.dataset.mode;
      this.layer.dataset.walks = '0';
    }
  }

  private removePaths(): void {
    this.drawnPoints = [];
    this.layer?.replaceChildren();
  }
}
