import { select } from 'd3-selection';
import 'd3-transition';
import { zoom, zoomIdentity, type D3ZoomEvent, type ZoomBehavior, type ZoomTransform } from 'd3-zoom';
import type { Frame } from './projection';
import { svg } from './svg';

/** An element drawn in screen space at a projected point, so it keeps its pixel size at any zoom. */
export interface Anchor {
  readonly element: SVGElement;
  /** The point in frame units; may change (a morphing map), then requestRender(). */
  x: number;
  y: number;
  /** Pixel offset from the point (labels move beside their station). */
  dx: number;
  dy: number;
}

export type LayerSpace = 'world' | 'screen';

/** Pixels along each side of the map covered by panels, which fitting keeps the map clear of. */
export interface Insets {
  top: number;
  right: number;
  bottom: number;
  left: number;
}

const NO_INSETS: Insets = { top: 0, right: 0, bottom: 0, left: 0 };

const FIT_PADDING_PX = 28;
/** growFitMargins refits at most this often per new frame, bounds or size (the names can change with the zoom). */
const MAX_MARGIN_ROUNDS = 2;
/** Fits whose margins are remembered (layouts x map sizes); forgotten all at once beyond. */
const MAX_REMEMBERED_FITS = 64;
/** Zoom limits, relative to the scale that fits the whole frame. */
const MIN_ZOOM = 0.5;
const MAX_ZOOM = 64;
const KEY_PAN_PX = 80;
const KEY_ZOOM = 1.5;
const REVEAL_MARGIN_PX = 48;

/** d3-zoom's own filter: no secondary buttons, no ctrl-drag (ctrl-wheel zooms). */
function defaultFilter(event: Event): boolean {
  const { ctrlKey, button } = event as MouseEvent;
  return (!ctrlKey || event.type === 'wheel') && !button;
}

function reducedMotion(): boolean {
  return window.matchMedia('(prefers-reduced-motion: reduce)').matches;
}

/**
 * A pannable, zoomable SVG map of one Frame. World layers scale with the zoom (their strokes
 * are non-scaling in CSS); screen layers hold anchors, repositioned on every frame of a zoom.
 * Wheel, drag, pinch and double-click come from d3-zoom; keys and buttons call zoomBy/fit.
 */
export class SvgMap {
  readonly element: HTMLDivElement;
  readonly svg: SVGSVGElement;
  private readonly world: SVGGElement;
  private readonly screen: SVGGElement;
  private readonly zoomBehavior: ZoomBehavior<SVGSVGElement, unknown>;
  private transform: ZoomTransform = zoomIdentity;
  private frame?: Frame;
  private anchors: Anchor[] = [];
  private renderRequest = 0;
  /** Until the user moves the map, a resize fits it again. */
  private followsFit = true;
  private readonly settleListeners = new Set<() => void>();
  private insets: () => Insets = () => NO_INSETS;
  /** Pixels per side fit() also keeps free: for names drawn beyond the fitted bounds (growFitMargins). */
  private margins: Insets = NO_INSETS;
  /** Margin rounds since the last new frame, bounds or size (growFitMargins stops at MAX_MARGIN_ROUNDS). */
  private marginRounds = 0;
  /**
   * The margins grown per fitted bounds and map size: the same layout at the same size fits
   * the same way again (back from another layout), whatever was shown in between.
   */
  private readonly marginsByFit = new Map<string, Insets>();
  private readonly renderListeners = new Set<() => void>();
  private gestureFilter: (event: Event) => boolean = () => true;
  /** Part of the frame fit() shows instead of the whole frame: [x0, y0, x1, y1]. */
  private fitBounds: [number, number, number, number] | null = null;
  /** While set, programmatic moves (an animation's frames) do not call the settle listeners. */
  private quiet = false;
  private gestures = 0;

  /** `doubleClickZoom: false` leaves double clicks to the view (map editors use clicks). */
  constructor(label: string, options: { doubleClickZoom?: boolean } = {}) {
    this.element = document.createElement('div');
    this.element.className = 'map';
    this.svg = svg('svg', { class: 'map-svg', role: 'img', 'aria-label': label, tabindex: 0 });
    this.world = svg('g', { class: 'map-world' });
    this.screen = svg('g', { class: 'map-screen' });
    this.svg.append(this.world, this.screen);
    this.element.append(this.svg);

    this.zoomBehavior = zoom<SVGSVGElement, unknown>()
      .on('zoom', (event: D3ZoomEvent<SVGSVGElement, unknown>) => {
        this.transform = event.transform;
        if (event.sourceEvent) {
          this.followsFit = false;
          this.gestures++;
        }
        this.requestRender();
      })
      .on('end', () => {
        if (!this.quiet) this.settle();
      })
      .filter((event: Event) => defaultFilter(event) && this.gestureFilter(event))
      // A click that wobbles a few pixels is still a click, not a pan.
      .clickDistance(4);
    select(this.svg).call(this.zoomBehavior);
    if (options.doubleClickZoom === false) select(this.svg).on('dblclick.zoom', null);
    this.svg.addEventListener('keydown', (event) => this.onKey(event));

    // Also fires when a hidden view is shown again.
    new ResizeObserver(() => {
      this.recallMargins();
      if (this.followsFit) this.fit(false);
      else this.settle();
    }).observe(this.element);
  }

  /**
   * Shows a new area and fits it, unless it is the area already shown (a reload of the same
   * city keeps the user's view).
   */
  setFrame(frame: Frame): void {
    const same = this.frame?.key === frame.key;
    this.frame = frame;
    if (same) return;
    // Set even when fit() cannot run yet (a hidden view): the first resize then fits.
    this.followsFit = true;
    this.marginsByFit.clear();
    this.recallMargins();
    this.fit(false);
  }

  /**
   * What fit() shows: a part of the frame [x0, y0, x1, y1] (a morphed map's extent), or null
   * for the whole frame. Does not move the map.
   */
  setFitBounds(bounds: [number, number, number, number] | null): void {
    this.fitBounds = bounds;
    this.recallMargins();
  }

  /** The key of what fit() fits: the bounds at the map's size. */
  private fitKey(): string {
    const { width, height } = this.size;
    return `${this.fitBounds ? this.fitBounds.map((v) => v.toFixed(1)).join(',') : 'frame'}@${width}x${height}`;
  }

  /** The margins grown before for what fit() fits now (none the first time), and new rounds. */
  private recallMargins(): void {
    this.margins = this.marginsByFit.get(this.fitKey()) ?? NO_INSETS;
    this.marginRounds = 0;
  }

  /**
   * The map element's part fit() fills, in client pixels: the element less the panels' insets
   * (as fit() counts them). What is drawn outside it after a fit is cut off or covered.
   */
  fitArea(): DOMRect {
    const box = this.element.getBoundingClientRect();
    const { width, height } = this.size;
    let { top, right, bottom, left } = this.insets();
    if (left + right > width / 2) left = right = 0;
    if (top + bottom > height / 2) top = bottom = 0;
    return new DOMRect(box.left + left, box.top + top, width - left - right, height - top - bottom);
  }

  /**
   * Station names keep their size in pixels, so a fit of the stations' bounds can put the
   * outer names off the map (a phone's narrow screen). Called with how far names stick out of
   * fitArea() per side after a fit, this widens those sides' margins by as much and fits
   * again, while the map follows its fit; a few rounds at most, since other names may show at
   * the new zoom. True when it refitted.
   */
  growFitMargins(over: Insets): boolean {
    if (!this.followsFit || this.marginRounds >= MAX_MARGIN_ROUNDS) return false;
    const grow = (side: keyof Insets) => Math.max(0, Math.ceil(over[side]));
    if (grow('top') + grow('right') + grow('bottom') + grow('left') === 0) return false;
    this.marginRounds += 1;
    const m = this.margins;
    this.margins = { top: m.top + grow('top'), right: m.right + grow('right'), bottom: m.bottom + grow('bottom'), left: m.left + grow('left') };
    if (this.marginsByFit.size >= MAX_REMEMBERED_FITS) this.marginsByFit.clear();
    this.marginsByFit.set(this.fitKey(), this.margins);
    this.fit(false);
    return true;
  }

  /** True until the user moves the map: a resize (or a view that wants to) fits it again. */
  get followingFit(): boolean {
    return this.followsFit;
  }

  /** Counts the user's pans and zooms (an animation that moves the map stops when it changes). */
  get gestureCount(): number {
    return this.gestures;
  }

  /** Tells fit() which parts of the map are covered (by a legend, say); asked at every fit. */
  setFitInsets(insets: () => Insets): void {
    this.insets = insets;
  }

  /** A new group in the given space, drawn above the layers added before it. */
  addLayer(name: string, space: LayerSpace): SVGGElement {
    const layer = svg('g', { class: `layer layer-${name}` });
    (space === 'world' ? this.world : this.screen).append(layer);
    return layer;
  }

  /** Removes every layer and anchor. */
  clear(): void {
    this.world.replaceChildren();
    this.screen.replaceChildren();
    this.anchors = [];
  }

  /** Forgets anchors (their elements are the caller's to remove). */
  removeAnchors(anchors: Iterable<Anchor>): void {
    const gone = new Set(anchors);
    if (gone.size > 0) this.anchors = this.anchors.filter((anchor) => !gone.has(anchor));
  }

  anchor(element: SVGElement, [x, y]: [number, number]): Anchor {
    const anchor: Anchor = { element, x, y, dx: 0, dy: 0 };
    this.anchors.push(anchor);
    this.place(anchor);
    return anchor;
  }

  /** Screen position (CSS pixels within the map) of a projected point. */
  toScreen(x: number, y: number): [number, number] {
    return this.transform.apply([x, y]);
  }

  /** The projected point at a screen position: toScreen's inverse. */
  toFrame(sx: number, sy: number): [number, number] {
    return this.transform.invert([sx, sy]);
  }

  /** The current pan and zoom: screen = frame × k + (x, y). */
  get view(): { x: number; y: number; k: number } {
    const { x, y, k } = this.transform;
    return { x, y, k };
  }

  /** Calls the listener on every rendered frame (after pans, zooms and requestRender). */
  onRender(listener: () => void): () => void {
    this.renderListeners.add(listener);
    return () => this.renderListeners.delete(listener);
  }

  /**
   * Asked before a mouse, touch or wheel event may start a pan or zoom; false leaves the
   * gesture to the view (dragging a handle, drawing a line).
   */
  setGestureFilter(filter: (event: Event) => boolean): void {
    this.gestureFilter = filter;
  }

  /** Screen pixels per frame unit. */
  get scale(): number {
    return this.transform.k;
  }

  get size(): { width: number; height: number } {
    return { width: this.svg.clientWidth, height: this.svg.clientHeight };
  }

  /**
   * Calls the listener when a zoom or pan ends, after fitting, and after a resize.
   * Returns the function that stops it.
   */
  onSettle(listener: () => void): () => void {
    this.settleListeners.add(listener);
    return () => this.settleListeners.delete(listener);
  }

  requestRender(): void {
    if (this.renderRequest) return;
    this.renderRequest = requestAnimationFrame(() => {
      this.renderRequest = 0;
      this.render();
    });
  }

  /** The pan and zoom fit() would go to, or null when the map has no size or frame yet. */
  fitTransform(): ZoomTransform | null {
    const frame = this.frame;
    const { width, height } = this.size;
    if (!frame || width === 0 || height === 0) return null;
    const pad = Math.min(FIT_PADDING_PX, width / 8, height / 8);
    let { top, right, bottom, left } = this.insets();
    // Panels that would leave the map less than half the room are ignored: better under a panel than tiny.
    if (left + right > width / 2) left = right = 0;
    if (top + bottom > height / 2) top = bottom = 0;
    const k = Math.min((width - left - right - 2 * pad) / frame.width, (height - top - bottom - 2 * pad) / frame.height);
    // The zoom limits stay those of the whole frame; fitBounds only says what to show.
    const [bx0, by0, bx1, by1] = this.fitBounds ?? [0, 0, frame.width, frame.height];
    // The names' margins (growFitMargins), at most a third of each direction's room.
    const shrink = (a: number, b: number, room: number) => (a + b > room / 3 ? room / 3 / (a + b) : 1);
    const sx = shrink(this.margins.left, this.margins.right, width - left - right - 2 * pad);
    const sy = shrink(this.margins.top, this.margins.bottom, height - top - bottom - 2 * pad);
    left += this.margins.left * sx;
    right += this.margins.right * sx;
    top += this.margins.top * sy;
    bottom += this.margins.bottom * sy;
    const fitK = Math.min(
      (width - left - right - 2 * pad) / Math.max(bx1 - bx0, 1e-9),
      (height - top - bottom - 2 * pad) / Math.max(by1 - by0, 1e-9),
      k * MAX_ZOOM,
    );
    this.zoomBehavior
      .scaleExtent([k * MIN_ZOOM, k * MAX_ZOOM])
      .translateExtent([
        [-frame.width, -frame.height],
        [2 * frame.width, 2 * frame.height],
      ]);
    return zoomIdentity
      .translate(left + (width - left - right - (bx1 - bx0) * fitK) / 2 - bx0 * fitK, top + (height - top - bottom - (by1 - by0) * fitK) / 2 - by0 * fitK)
      .scale(fitK);
  }

  fit(animate = true): void {
    const target = this.fitTransform();
    if (!target) return;
    this.followsFit = true;
    this.animated(animate, 350).call(this.zoomBehavior.transform, target);
  }

  /**
   * Sets the pan and zoom at once, without telling the settle listeners: for the frames of an
   * animation, which calls settle() when it ends. Keeps followsFit as it is.
   */
  jumpTo(x: number, y: number, k: number): void {
    this.quiet = true;
    try {
      select(this.svg).interrupt().call(this.zoomBehavior.transform, zoomIdentity.translate(x, y).scale(k));
    } finally {
      this.quiet = false;
    }
  }

  /** Calls the settle listeners (after an animation moved the map with jumpTo). */
  settle(): void {
    this.settleListeners.forEach((listener) => listener());
  }

  /** Zooms in by `factor` and centres the projected point. */
  zoomTo(x: number, y: number, factor: number): void {
    const { width, height } = this.size;
    const [kMin, kMax] = this.zoomBehavior.scaleExtent();
    const k = Math.max(kMin, Math.min(kMax, this.transform.k * factor));
    this.followsFit = false;
    this.animated(true, 450).call(this.zoomBehavior.transform, zoomIdentity.translate(width / 2 - x * k, height / 2 - y * k).scale(k));
  }

  zoomBy(factor: number): void {
    this.followsFit = false;
    this.animated(true, 200).call(this.zoomBehavior.scaleBy, factor);
  }

  panBy(dx: number, dy: number): void {
    this.followsFit = false;
    this.animated(true, 150).call(this.zoomBehavior.translateBy, dx / this.transform.k, dy / this.transform.k);
  }

  /** Pans so the projected point is in view, if it is not (or is near an edge). */
  reveal(x: number, y: number): void {
    const [sx, sy] = this.toScreen(x, y);
    const { width, height } = this.size;
    const margin = Math.min(REVEAL_MARGIN_PX, width / 4, height / 4);
    if (sx >= margin && sy >= margin && sx <= width - margin && sy <= height - margin) return;
    this.followsFit = false;
    this.animated(true, 350).call(this.zoomBehavior.translateTo, x, y);
  }

  private animated(animate: boolean, ms: number) {
    const target = select(this.svg);
    return animate && !reducedMotion() ? target.transition().duration(ms) : target;
  }

  private render(): void {
    const { x, y, k } = this.transform;
    this.world.setAttribute('transform', `translate(${x},${y}) scale(${k})`);
    for (const anchor of this.anchors) this.place(anchor);
    this.renderListeners.forEach((listener) => listener());
  }

  private place(anchor: Anchor): void {
    const [sx, sy] = this.transform.apply([anchor.x, anchor.y]);
    anchor.element.setAttribute('transform', `translate(${(sx + anchor.dx).toFixed(1)},${(sy + anchor.dy).toFixed(1)})`);
  }

  private onKey(event: KeyboardEvent): void {
    const actions: Record<string, () => void> = {
      '+': () => this.zoomBy(KEY_ZOOM),
      '=': () => this.zoomBy(KEY_ZOOM),
      '-': () => this.zoomBy(1 / KEY_ZOOM),
      '0': () => this.fit(),
      ArrowLeft: () => this.panBy(KEY_PAN_PX, 0),
      ArrowRight: () => this.panBy(-KEY_PAN_PX, 0),
      ArrowUp: () => this.panBy(0, KEY_PAN_PX),
      ArrowDown: () => this.panBy(0, -KEY_PAN_PX),
    };
    const action = actions[event.key];
    if (!action || event.ctrlKey || event.metaKey || event.altKey) return;
    event.preventDefault();
    action();
  }
}
