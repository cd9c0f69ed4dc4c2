import type { DeformResponse, FocusRegion, LonLat } from '../api/types';
import { distanceMeters } from '../map/distance';
import { svg } from '../map/svg';
import { h } from '../ui/dom';
import type { Frame } from '../map/projection';
import { clamp, metersPerUnit, roundLonLat } from './geometry';
import { circle, label, polyline, polylineDistance } from './overlay';
import type { DeformTool, ScreenPoint, ToolContext, ToolRequest } from './tool';

const MAX_REGIONS = 32;
const MIN_RADIUS_M = 10;
const DEFAULT_SCALE = 3;
const SCALE_RANGE = { min: 1.2, max: 10, step: 0.1 };
const RING_STEPS = 72;
/** Hit distances in pixels: the centre handle, and the rim on either side of the line. */
const HANDLE_HIT_PX = 11;
const RIM_HIT_PX = 7;
/** A region's centre is drawn within this many pixels of where the user put it, after at most MAX_CORRECTIONS more requests. */
const CORRECTED_PX = 2;
const MAX_CORRECTIONS = 6;
const CORRECTION_STEP = 0.7;
/** Radius sliders are logarithmic: this many steps from MIN_RADIUS_M to the network's size. */
const RADIUS_STEPS = 1000;

interface Region {
  id: number;
  /** On the original map. */
  center: LonLat;
  radiusM: number;
  scale: number;
  /**
   * This region as it is in the answer drawn now (none before its first answer), and where the
   * server's grid put its centre and rim (frame coordinates): the true image of the circle.
   */
  shown?: { center: LonLat; radiusM: number; handle?: [number, number]; ring?: [number, number][] };
  /**
   * Where the centre handle is held on the deformed map (frame coordinates): under the pointer
   * while dragged, and there until the answer for the region's latest state is drawn.
   */
  pin?: [number, number];
  /**
   * Where the user put the centre (frame coordinates of the deformed map: the click, or the
   * handle's release): the region's centre on the original map is corrected until the grid puts
   * it there, as the focus pushes its own centre aside (Monaco: 23 px at Z = 3).
   */
  target?: [number, number];
  corrections?: number;
}

type Drag =
  | { kind: 'move'; region: Region; cursor0: [number, number]; center0: [number, number]; pin0: [number, number] }
  | { kind: 'radius'; region: Region; distance0: number; radius0: number };

type Hit = { kind: 'move' | 'radius'; region: Region };

/** One region's controls in the side panel, updated in place so a slider keeps working while dragged. */
class RegionRow {
  readonly element: HTMLLIElement;
  private readonly title: HTMLButtonElement;
  private readonly scale: HTMLInputElement;
  private readonly scaleOut: HTMLOutputElement;
  private readonly radius: HTMLInputElement;
  private readonly radiusOut: HTMLOutputElement;

  constructor(
    readonly region: Region,
    private readonly tool: FocusTool,
  ) {
    this.title = h('button', { type: 'button', class: 'region-title' });
    this.title.addEventListener('click', () => tool.select(region));
    const remove = h('button', { type: 'button', class: 'region-remove', 'aria-label': 'Remove this region', title: 'Remove this region' }, '×');
    remove.addEventListener('click', () => tool.remove(region));
    this.scale = h('input', { type: 'range', min: SCALE_RANGE.min, max: SCALE_RANGE.max, step: SCALE_RANGE.step, 'data-testid': 'region-scale' });
    this.scaleOut = h('output', {});
    this.radius = h('input', { type: 'range', min: 0, max: RADIUS_STEPS, step: 1, 'data-testid': 'region-radius' });
    this.radiusOut = h('output', {});
    this.scale.addEventListener('input', () => tool.setScale(region, Number(this.scale.value)));
    this.radius.addEventListener('input', () => tool.setRadius(region, tool.radiusFromSlider(Number(this.radius.value))));
    for (const slider of [this.scale, this.radius]) {
      slider.addEventListener('pointerdown', () => tool.sliding(true));
      slider.addEventListener('change', () => tool.sliding(false));
    }
    this.element = h(
      'li',
      { class: 'region-item' },
      h('div', { class: 'region-head' }, this.title, remove),
      h('label', { class: 'slider-row' }, h('span', {}, 'Scale Z'), this.scale, this.scaleOut),
      h('label', { class: 'slider-row' }, h('span', {}, 'Radius'), this.radius, this.radiusOut),
    );
  }

  update(index: number, selected: boolean): void {
    this.title.textContent = `Region ${index + 1}`;
    this.element.classList.toggle('selected', selected);
    this.title.setAttribute('aria-pressed', String(selected));
    if (document.activeElement !== this.scale) this.scale.value = String(this.region.scale);
    if (document.activeElement !== this.radius) this.radius.value = String(this.tool.sliderFromRadius(this.region.radiusM));
    this.scaleOut.textContent = `${this.region.scale.toFixed(1)}×`;
    this.radiusOut.textContent = formatMeters(this.region.radiusM);
  }
}

function formatMeters(meters: number): string {
  return meters < 1000 ? `${Math.round(meters)} m` : `${(meters / 1000).toFixed(2)} km`;
}

/**
 * Focus: circular regions of the original map drawn Z times larger. Click adds a region, its
 * centre handle moves it, its rim resizes it; sliders set Z and the radius. The regions are
 * drawn where the deformation put them (the original circle carried by the displacement).
 */
export class FocusTool implements DeformTool {
  readonly kind = 'focus' as const;
  readonly panel: HTMLElement;
  private readonly list: HTMLOListElement;
  private readonly empty: HTMLElement;
  private readonly clearButton: HTMLButtonElement;
  private context: ToolContext | null = null;
  private regions: Region[] = [];
  private rows = new Map<number, RegionRow>();
  private selected?: Region;
  private nextId = 1;
  private drag?: Drag;
  private hovered?: Hit;
  private maxRadiusM = 10000;
  /** Region shapes on the drawn map, until the state or the drawn deformation changes. */
  private shapes = new Map<Region, { handle: [number, number]; ring: [number, number][] }>();
  private shapesFor?: unknown;
  /** Which region each sent request's entries belong to. */
  private readonly sentIds = new WeakMap<FocusRegion[], number[]>();

  constructor() {
    this.list = h('ol', { class: 'region-list', 'data-testid': 'region-list' });
    this.empty = h('p', { class: 'note' }, 'No focus regions yet.');
    this.clearButton = h('button', { type: 'button', class: 'button button-quiet' }, 'Remove all regions');
    this.clearButton.addEventListener('click', () => {
      this.regions = [];
      this.selected = undefined;
      this.changed();
    });
    this.panel = h(
      'div',
      { class: 'tool-panel' },
      h(
        'p',
        { class: 'hint' },
        'Tap or click the map to enlarge the streets around that spot (a focus region) while the rest of the map gives way. Drag a region’s centre to move it and its rim to resize it; Delete removes the selected one.',
      ),
      this.list,
      this.empty,
      this.clearButton,
    );
    this.syncPanel();
  }

  reset(context: ToolContext | null): void {
    this.context = context;
    this.regions = [];
    this.selected = undefined;
    this.drag = undefined;
    this.hovered = undefined;
    this.shapes.clear();
    if (context) {
      const { graph } = context;
      let west = Infinity, south = Infinity, east = -Infinity, north = -Infinity;
      for (let i = 0; i < graph.nodeCount; i++) {
        west = Math.min(west, graph.lonLat[2 * i]!);
        east = Math.max(east, graph.lonLat[2 * i]!);
        south = Math.min(south, graph.lonLat[2 * i + 1]!);
        north = Math.max(north, graph.lonLat[2 * i + 1]!);
      }
      this.maxRadiusM = Math.max(MIN_RADIUS_M * 10, distanceMeters([west, south], [east, north]) / 2);
    }
    this.syncPanel();
  }

  request(): ToolRequest | null {
    if (this.regions.length === 0) return null;
    const regions: FocusRegion[] = this.regions.map((region) => ({
      center: region.center,
      radius_m: Math.round(region.radiusM * 10) / 10,
      scale: region.scale,
    }));
    this.sentIds.set(regions, this.regions.map((region) => region.id));
    // Each region's centre and rim, for the server to say where its grid put them.
    const frame = this.context?.frame;
    const mapPoints = frame ? this.regions.flatMap((region) => circlePoints(frame, region.center, region.radiusM)) : undefined;
    return mapPoints ? { regions, map_points: mapPoints } : { regions };
  }

  applied(result: DeformResponse, request: ToolRequest): void {
    if (!('regions' in request)) return;
    const ids = this.sentIds.get(request.regions) ?? [];
    const byId = new Map(this.regions.map((region) => [region.id, region]));
    for (const region of this.regions) region.shown = undefined;
    const mapped = 'map_points' in request && request.map_points && result.mapped_points?.length === request.map_points.length ? result.mapped_points : undefined;
    const frame = this.context?.frame;
    request.regions.forEach((sent, i) => {
      const region = byId.get(ids[i] ?? -1);
      if (!region || !('center' in sent)) return;
      region.shown = { center: sent.center, radiusM: sent.radius_m };
      if (mapped && frame) {
        const points = mapped.slice(i * (RING_STEPS + 1), (i + 1) * (RING_STEPS + 1)).map((p) => frame.project(p));
        region.shown.handle = points[0];
        region.shown.ring = points.slice(1);
      }
    });
    this.shapes.clear();
    let corrected = false;
    for (const region of this.regions) {
      const settled = region.shown && sameCenter(region.shown.center, region.center) && Math.abs(region.shown.radiusM - region.radiusM) < 0.05;
      if (!settled || this.drag?.region === region) continue;
      if (region.target && region.shown?.handle && frame && this.context) corrected = this.correct(region, region.shown.handle) || corrected;
      if (!region.target) region.pin = undefined;
    }
    if (corrected) this.changed();
  }

  /**
   * Moves the region's centre on the original map towards where the user wants it drawn: by
   * CORRECTION_STEP of the distance between that and where the grid put it (the whole step
   * overshoots: which roads fall in the region changes as it moves), up to MAX_CORRECTIONS
   * times, until they are within CORRECTED_PX (Monaco: 23 px, then 12, 4, 2, 1 px). True when
   * it moved.
   */
  private correct(region: Region, handle: [number, number]): boolean {
    const context = this.context!;
    const target = region.target!;
    const [tx, ty] = context.map.toScreen(...target);
    const [hx, hy] = context.map.toScreen(...handle);
    if (Math.hypot(tx - hx, ty - hy) <= CORRECTED_PX || (region.corrections ?? 0) >= MAX_CORRECTIONS) {
      region.target = region.corrections = undefined;
      return false;
    }
    region.corrections = (region.corrections ?? 0) + 1;
    const [cx, cy] = context.frame.project(region.center);
    const step = CORRECTION_STEP;
    region.center = roundLonLat(context.frame.unproject(cx + step * (target[0] - handle[0]), cy + step * (target[1] - handle[1])));
    region.pin = target;  // drawn where the user put it meanwhile
    return true;
  }

  pointerDown(point: ScreenPoint): boolean {
    const context = this.context;
    const hit = this.hitTest(point);
    if (!context || !hit) return false;
    const { region } = hit;
    this.select(region);
    const { handle } = this.geometry(region);
    if (hit.kind === 'move') {
      this.drag = { kind: 'move', region, cursor0: context.map.toFrame(...point), center0: context.frame.project(region.center), pin0: handle };
    } else {
      const [hx, hy] = context.map.toScreen(...handle);
      region.pin = handle;
      this.drag = { kind: 'radius', region, distance0: Math.max(1, Math.hypot(point[0] - hx, point[1] - hy)), radius0: region.radiusM };
    }
    context.dragging(true);
    return true;
  }

  pointerMove(point: ScreenPoint): void {
    const context = this.context;
    const drag = this.drag;
    if (!context || !drag) return;
    const { region } = drag;
    if (drag.kind === 'move') {
      const [x, y] = context.map.toFrame(...point);
      const dx = x - drag.cursor0[0];
      const dy = y - drag.cursor0[1];
      region.center = roundLonLat(context.frame.unproject(drag.center0[0] + dx, drag.center0[1] + dy));
      region.pin = [drag.pin0[0] + dx, drag.pin0[1] + dy];
    } else {
      const [hx, hy] = context.map.toScreen(...(region.pin ?? this.geometry(region).handle));
      region.radiusM = this.clampRadius((drag.radius0 * Math.hypot(point[0] - hx, point[1] - hy)) / drag.distance0);
    }
    this.changed();
  }

  pointerUp(): void {
    const drag = this.drag;
    if (!drag) return;
    this.drag = undefined;
    // A moved centre stays where it was let go.
    if (drag.kind === 'move' && drag.region.pin) {
      drag.region.target = drag.region.pin;
      drag.region.corrections = 0;
    }
    this.context?.dragging(false);
  }

  click(point: ScreenPoint): void {
    const context = this.context;
    if (!context) return;
    if (this.regions.length >= MAX_REGIONS) {
      context.notify(`At most ${MAX_REGIONS} focus regions: remove one first.`);
      return;
    }
    const { map, frame } = context;
    const [x, y] = context.displacement().inverse(...map.toFrame(...point));
    const { width, height } = map.size;
    const radiusUnits = Math.min(width, height) / 10 / map.scale;
    const region: Region = {
      id: this.nextId++,
      center: roundLonLat(frame.unproject(x, y)),
      radiusM: this.clampRadius(radiusUnits * metersPerUnit(frame, x, y)),
      scale: DEFAULT_SCALE,
      target: map.toFrame(...point),
    };
    this.regions.push(region);
    this.selected = region;
    this.changed();
  }

  hover(point: ScreenPoint | null): string {
    const hit = point ? this.hitTest(point) : undefined;
    if (hit?.region !== this.hovered?.region || hit?.kind !== this.hovered?.kind) {
      this.hovered = hit;
      this.context?.redraw();
    }
    if (!hit) return 'crosshair';
    return hit.kind === 'move' ? 'move' : 'ew-resize';
  }

  key(event: KeyboardEvent): boolean {
    if ((event.key === 'Delete' || event.key === 'Backspace') && this.selected) {
      this.remove(this.selected);
      return true;
    }
    return false;
  }

  highlighted(): number[] {
    return [];
  }

  render(layer: SVGGElement): void {
    const context = this.context;
    if (!context) return;
    const toScreen = (p: [number, number]) => context.map.toScreen(...p);
    for (const region of this.regions) {
      const { handle, ring } = this.geometry(region);
      const selected = region === this.selected;
      const hovered = this.hovered?.region === region ? this.hovered.kind : this.drag?.region === region ? this.drag.kind : undefined;
      const group = svg('g', { class: `focus-region${selected ? ' selected' : ''}` });
      const outline = polyline(ring.map(toScreen), `focus-ring${hovered === 'radius' ? ' active' : ''}`, true);
      const centre = toScreen(handle);
      group.append(outline, circle(centre, hovered === 'move' ? 8 : 6, 'focus-handle'), label([centre[0] + 10, centre[1] - 8], `${region.scale.toFixed(1)}×`, 'focus-label'));
      layer.append(group);
    }
  }

  // Called by the panel rows.

  select(region: Region): void {
    this.selected = region;
    this.syncPanel();
    this.context?.redraw();
  }

  remove(region: Region): void {
    this.regions = this.regions.filter((other) => other !== region);
    if (this.selected === region) this.selected = this.regions[this.regions.length - 1];
    if (this.drag?.region === region) this.pointerUp();
    this.changed();
  }

  setScale(region: Region, scale: number): void {
    region.scale = clamp(scale, SCALE_RANGE.min, SCALE_RANGE.max);
    this.selected = region;
    this.changed();
  }

  setRadius(region: Region, radiusM: number): void {
    region.radiusM = this.clampRadius(radiusM);
    this.selected = region;
    this.changed();
  }

  sliding(active: boolean): void {
    this.context?.dragging(active);
  }

  radiusFromSlider(value: number): number {
    return MIN_RADIUS_M * (this.maxRadiusM / MIN_RADIUS_M) ** (value / RADIUS_STEPS);
  }

  sliderFromRadius(radiusM: number): number {
    return Math.round((Math.log(radiusM / MIN_RADIUS_M) / Math.log(this.maxRadiusM / MIN_RADIUS_M)) * RADIUS_STEPS);
  }

  private clampRadius(radiusM: number): number {
    return clamp(radiusM, MIN_RADIUS_M, this.maxRadiusM);
  }

  private changed(): void {
    this.shapes.clear();
    this.syncPanel();
    this.context?.changed();
  }

  private syncPanel(): void {
    const ids = new Set(this.regions.map((region) => region.id));
    for (const [id, row] of this.rows) {
      if (!ids.has(id)) {
        row.element.remove();
        this.rows.delete(id);
      }
    }
    this.regions.forEach((region, index) => {
      let row = this.rows.get(region.id);
      if (!row) {
        row = new RegionRow(region, this);
        this.rows.set(region.id, row);
        this.list.append(row.element);
      }
      row.update(index, region === this.selected);
    });
    this.empty.hidden = this.regions.length > 0;
    this.clearButton.hidden = this.regions.length === 0;
  }

  /**
   * The region on the deformed map (frame coordinates): its centre handle and rim. The shape is
   * the answered circle carried by the displacement; a held handle moves it, a new radius scales it.
   */
  private geometry(region: Region): { handle: [number, number]; ring: [number, number][] } {
    const context = this.context!;
    const displacement = context.displacement();
    if (this.shapesFor !== displacement) {
      this.shapes.clear();
      this.shapesFor = displacement;
    }
    let shape = this.shapes.get(region);
    if (!shape) {
      shape = this.computeGeometry(region);
      this.shapes.set(region, shape);
    }
    return shape;
  }

  private computeGeometry(region: Region): { handle: [number, number]; ring: [number, number][] } {
    const context = this.context!;
    const base = region.shown ?? { center: region.center, radiusM: region.radiusM };
    let handle0: [number, number];
    let ring0: [number, number][];
    if (base.handle && base.ring) {
      // Where the server's grid put the circle (the map drawn now is that answer).
      handle0 = base.handle;
      ring0 = base.ring;
    } else {
      // Before an answer: the circle carried by the displacement between drawn maps.
      const displacement = context.displacement();
      const [cx, cy] = context.frame.project(base.center);
      const r = base.radiusM / metersPerUnit(context.frame, cx, cy);
      handle0 = displacement.forward(cx, cy);
      ring0 = [];
      for (let i = 0; i < RING_STEPS; i++) {
        const angle = (2 * Math.PI * i) / RING_STEPS;
        ring0.push(displacement.forward(cx + r * Math.cos(angle), cy + r * Math.sin(angle)));
      }
    }
    // A held handle moves the shape, a new radius scales it, until the answer for them comes.
    const handle = region.pin ?? handle0;
    const grow = region.radiusM / base.radiusM;
    const ring = ring0.map(([x, y]): [number, number] => [handle[0] + (x - handle0[0]) * grow, handle[1] + (y - handle0[1]) * grow]);
    return { handle, ring };
  }

  private hitTest(point: ScreenPoint): Hit | undefined {
    const context = this.context;
    if (!context) return undefined;
    // The selected region first, then the newest: the one drawn on top.
    const order = [...this.regions].reverse().sort((a, b) => Number(b === this.selected) - Number(a === this.selected));
    const shapes = order.map((region) => ({ region, ...this.geometry(region) }));
    for (const { region, handle } of shapes) {
      const [hx, hy] = context.map.toScreen(...handle);
      if (Math.hypot(point[0] - hx, point[1] - hy) <= HANDLE_HIT_PX) return { kind: 'move', region };
    }
    for (const { region, ring } of shapes) {
      const screenRing = ring.map((p) => context.map.toScreen(...p));
      if (polylineDistance(point, screenRing, true) <= RIM_HIT_PX) return { kind: 'radius', region };
    }
    return undefined;
  }
}

/** A circle on the original map: its centre, then RING_STEPS points of its rim ([lon, lat]). */
function circlePoints(frame: Frame, center: LonLat, radiusM: number): LonLat[] {
  const [cx, cy] = frame.project(center);
  const r = radiusM / metersPerUnit(frame, cx, cy);
  const points: LonLat[] = [center];
  for (let i = 0; i < RING_STEPS; i++) {
    const angle = (2 * Math.PI * i) / RING_STEPS;
    points.push(roundLonLat(frame.unproject(cx + r * Math.cos(angle), cy + r * Math.sin(angle))));
  }
  return points;
}

function sameCenter(a: LonLat, b: LonLat): boolean {
  return Math.abs(a[0] - b[0]) < 1e-9 && Math.abs(a[1] - b[1]) < 1e-9;
}
