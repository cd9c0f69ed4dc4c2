import { fetchLayout, isAbort, type LayoutAnswer, type LayoutRoadsResponse } from '../api/client';
import type { InterestParams } from '../api/interests';
import type { CitySummary, LayoutImprovedEvent, LayoutParams, VisualWorthRaster, XY } from '../api/types';
import type { Frame } from '../map/projection';
import type { SvgMap } from '../map/svg-map';
import type { MapNotice } from '../ui/notice';
import { geoGrid, layoutGeometry, Placement, serverLabels } from './layout-geometry';
import type { LayoutInfo } from './layout-info';
import type { MapMode, MapOptions } from './map-options';
import type { MetroLayers, ServerLabels } from './metro-layers';
import { carry, easeInOutCubic, geometryBounds, Morph, type Geometry, type Pt } from './morph';

const MORPH_MS = 750;

/** The layouts of a city by parameters: what the client asks for (see layoutFor). */
const layoutKey = (cityId: string, params: InterestParams) => `${cityId}|${params.lengths}|${params.solver}|${params.interests ?? ''}`;

const lerp = (a: number, b: number, t: number) => a + (b - a) * t;

function reducedMotion(): boolean {
  return window.matchMedia('(prefers-reduced-motion: reduce)').matches;
}

/** A layout ready to draw: the answer, where it goes on the map, and the two drawings it morphs between. */
export interface LayoutEntry extends LayoutAnswer {
  key: string;
  params: LayoutParams;
  placement: Placement;
  /** The octilinear drawing. */
  geometry: Geometry;
  /** The geographic drawing with the layout's regular mesh. */
  geoGeometry: Geometry;
  /** The POIs' warped positions in the layout frame, by id. */
  poiPositions: Map<string, XY>;
  /** The server's station names for this layout, or null (an older server gave none). */
  labels: ServerLabels | null;
  /** The heat map of the whole mesh (asked for once, when first shown). */
  heat?: Promise<VisualWorthRaster>;
  /** The streets warped into this layout (asked for once, when first shown); null: the city has no road network. */
  roads?: Promise<LayoutRoadsResponse | null>;
}

/** What the layout controller needs of the view: the city drawn and what goes with a morph. */
export interface LayoutHost {
  city(): CitySummary | undefined;
  layers(): MetroLayers | undefined;
  frame(): Frame | undefined;
  /** The drawn city's load: aborted when another city is drawn. */
  signal(): AbortSignal | undefined;
  /** The parameters of the layout the switches and interests ask for. */
  params(): InterestParams;
  /** A morph starts (`morphing` is true already): what belongs to one drawing goes. */
  morphStarted(): void;
  /** A morph ended (`drawnMode` is its target); the map settles right after. */
  morphEnded(): void;
}

/**
 * Geographic <-> octilinear: asks for the layouts (once per city and parameters), morphs between
 * the drawings while the view follows, and swaps in layouts the server improved.
 *
 * Sets on the map element: data-mode, data-transition, data-morph-to, data-morph-frames,
 * data-layout, data-layout-solver and data-layout-swaps (for tests).
 */
export class LayoutController {
  /** Layouts of the drawn city by parameters, asked for or ready. */
  private readonly layouts = new Map<string, Promise<LayoutEntry>>();
  private readonly layoutsReady = new Set<string>();
  private shownLayout?: LayoutEntry;
  /** Counts mode and parameter changes: an answer for an older one is not drawn. */
  private modeRequest = 0;
  private animation = 0;
  private morphRunning = false;
  /** The drawing shown once the morph is over: what clusters and heat map are asked for. */
  private mode: MapMode = 'geographic';

  constructor(
    private readonly map: SvgMap,
    private readonly info: LayoutInfo,
    private readonly notice: MapNotice,
    private readonly options: MapOptions,
    private readonly host: LayoutHost,
  ) {}

  /** The layout drawn (octilinear) or last drawn (its mesh stays for the warp grid). */
  get shown(): LayoutEntry | undefined {
    return this.shownLayout;
  }

  /** The layout drawn when the octilinear map is (not morphing to the geographic one). */
  get drawnLayout(): LayoutEntry | undefined {
    return this.mode === 'octilinear' ? this.shownLayout : undefined;
  }

  get morphing(): boolean {
    return this.morphRunning;
  }

  get drawnMode(): MapMode {
    return this.mode;
  }

  /** Changes with every mode or parameter change (an answer asked for before one is stale). */
  get request(): number {
    return this.modeRequest;
  }

  /** Another city (or none): stops the morph and forgets the layouts. */
  reset(): void {
    cancelAnimationFrame(this.animation);
    this.morphRunning = false;
    this.mode = 'geographic';
    this.modeRequest++;
    this.layouts.clear();
    this.layoutsReady.clear();
    this.shownLayout = undefined;
  }

  /** The layout for the parameters, asked for once per city and parameters (a failure is forgotten). */
  private layoutFor(city: CitySummary, params: LayoutParams, signal: AbortSignal): Promise<LayoutEntry> {
    const key = layoutKey(city.id, params);
    let entry = this.layouts.get(key);
    if (!entry) {
      const layers = this.host.layers()!;
      const frame = this.host.frame()!;
      entry = fetchLayout(city.id, params, signal).then((answer) => {
        const placement = Placement.fit(answer.layout, frame);
        this.layoutsReady.add(key);
        const geometry = layoutGeometry(answer.layout, placement, layers.drawnEdges, layers.geo);
        return {
          ...answer,
          key,
          params,
          placement,
          geometry,
          // The geographic drawing keeps the layout's line order (the same track, the same sides).
          geoGeometry: { ...layers.geo, grid: geoGrid(answer.layout, placement), orders: geometry.orders },
          labels: serverLabels(answer.layout, placement),
          poiPositions: new Map(answer.layout.pois.features.map((poi) => [poi.properties.id, poi.geometry.coordinates])),
        };
      });
      entry.catch(() => this.layouts.delete(key));
      this.layouts.set(key, entry);
    }
    return entry;
  }

  async showOctilinear(): Promise<void> {
    const city = this.host.city();
    const layers = this.host.layers();
    const signal = this.host.signal();
    if (!city || !layers || !signal) return;
    const request = ++this.modeRequest;
    const params = this.host.params();
    const key = layoutKey(city.id, params);
    const data = this.map.element.dataset;
    if (!this.layoutsReady.has(key)) {
      data.layout = 'loading';
      this.info.loading(
        city.name,
        params.solver === 'mip'
          ? 'The MIP solver runs for up to 10 s. The map stays geographic until the layout arrives.'
          : 'The first layout of a city takes up to ~10 s for large networks (later ones are cached). The map stays geographic until it arrives.',
      );
    }
    let entry: LayoutEntry;
    try {
      entry = await this.layoutFor(city, params, signal);
    } catch (error) {
      if (isAbort(error) || request !== this.modeRequest || this.host.layers() !== layers) return;
      data.layout = 'error';
      // The layout drawn stays, and the switches say which one it is.
      if (this.shownLayout && this.mode === 'octilinear') {
        this.info.showLayout(this.shownLayout);
        this.options.setLayoutParams(this.shownLayout.params.lengths, this.shownLayout.params.solver);
      } else {
        this.info.hideLayout();
      }
      this.notice.error('layout', `Could not compute the octilinear layout of ${city.name}`, error, () => {
        this.options.setMode('octilinear');
        this.options.setLayoutParams(params.lengths, params.solver);
        void this.showOctilinear();
      });
      // Nothing else to show: back to the geographic map.
      if (this.mode !== 'octilinear') this.options.setMode('geographic');
      return;
    }
    if (request !== this.modeRequest || this.host.layers() !== layers) return;
    this.notice.clear('layout');
    this.shownLayout = entry;
    data.layout = 'ready';
    data.layoutSolver = entry.layout.solver.kind;
    this.info.showLayout(entry);
    this.morphTo(entry.geometry, 'octilinear', entry.labels);
  }

  showGeographic(): void {
    this.modeRequest++;
    const layers = this.host.layers();
    this.info.hideLayout();
    if (this.map.element.dataset.layout === 'loading') delete this.map.element.dataset.layout;
    if (!layers) return;
    this.morphTo(this.shownLayout?.geoGeometry ?? layers.geo, 'geographic', null);
  }

  /**
   * The server improved a default layout in the background (fewer bends, room for names). If it is
   * one this view asked for (same city version and parameters), the cached answer is dropped;
   * if it is the one drawn, the improved one is fetched and morphed in like any layout change:
   * no reload, and the view stays where the user put it (a fitted map stays fitted).
   */
  layoutImproved(event: LayoutImprovedEvent): void {
    const city = this.host.city();
    if (!city || event.city !== city.id || event.params.solver !== 'auto') return;
    const lengths = event.params.lengths;
    if (lengths !== 'visual-worth' && lengths !== 'uniform') return;
    const params: LayoutParams = { lengths, solver: 'auto' };
    const asked = this.layouts.get(layoutKey(city.id, params));
    if (asked) void this.swapImproved(city, params, asked, event);
  }

  private async swapImproved(
    city: CitySummary,
    params: LayoutParams,
    asked: Promise<LayoutEntry>,
    event: LayoutImprovedEvent,
  ): Promise<void> {
    const key = layoutKey(city.id, params);
    let old: LayoutEntry;
    try {
      old = await asked;
    } catch {
      return; // failed: forgotten already, the next request gets the improved one
    }
    const sameParams = Object.entries(old.layout.params).every(([name, value]) => event.params[name] === value);
    const stillAsked = this.host.city() === city && this.layouts.get(key) === asked;
    if (!stillAsked || old.layout.version !== event.version || !sameParams) return;
    if (old.layout.solver.improvement === 'applied') return; // asked for after the improvement
    this.layouts.delete(key);
    this.layoutsReady.delete(key);
    const signal = this.host.signal();
    if (!signal) return;
    let entry: LayoutEntry;
    try {
      entry = await this.layoutFor(city, params, signal);
    } catch {
      return; // the layout drawn stays; a later switch asks again
    }
    // Swapped in only where the old one is still what is drawn, or being morphed to.
    const current = this.host.params();
    const drawn = this.shownLayout === old && this.options.state.mode === 'octilinear';
    if (!drawn || current.lengths !== params.lengths || current.solver !== 'auto') return;
    const data = this.map.element.dataset;
    this.shownLayout = entry;
    data.layoutSolver = entry.layout.solver.kind;
    data.layoutSwaps = String(Number(data.layoutSwaps ?? 0) + 1);
    this.info.showLayout(entry);
    this.morphTo(entry.geometry, 'octilinear', entry.labels);
  }

  /**
   * Morphs from what is drawn (even halfway through another morph) to `target`, eased, while the
   * view follows: a fitted map is fitted to the target, otherwise the place at the centre of the
   * window stays there (carried by the nearby stations' moves). Clusters and heat map are hidden
   * meanwhile and asked for again at the end (LayoutHost).
   *
   * Every frame works with the map's size at that moment: a resize during the morph (a phone's
   * sheet folded) refits the map, and the frames after it must not pull it back to the old size.
   */
  private morphTo(target: Geometry, mode: MapMode, labels: ServerLabels | null): void {
    const layers = this.host.layers();
    if (!layers) return;
    // The octilinear layout comes with the server's station names; the geographic map places its own.
    layers.setServerLabels(labels);
    cancelAnimationFrame(this.animation);

    const from = layers.geometry;
    const morph = new Morph(from, target);
    this.map.setFitBounds(mode === 'octilinear' ? geometryBounds(target) : null);
    const size0 = this.map.size;
    const start = this.map.view;
    // A fitted map ends fitted (to its size at the end); otherwise the centre goes where the stations around it go.
    const fitting = this.map.followingFit && this.map.fitTransform() !== null;
    const centre0 = this.map.toFrame(size0.width / 2, size0.height / 2);
    const carried: Pt = fitting ? centre0 : carry(centre0, from.stations, target.stations);
    const gestures = this.map.gestureCount;
    const duration = reducedMotion() ? 0 : MORPH_MS;
    const data = this.map.element.dataset;
    this.morphRunning = true;
    this.host.morphStarted();
    data.transition = 'running';
    data.morphTo = mode;
    const started = performance.now();
    let frames = 0;

    const step = (now: number) => {
      const t = duration > 0 ? Math.min(1, (now - started) / duration) : 1;
      const e = easeInOutCubic(t);
      layers.setGeometry(morph.at(e), t >= 1);
      // The user's own pan or zoom meanwhile wins over the view's move.
      const { width, height } = this.map.size;
      if (this.map.gestureCount === gestures && width > 0 && height > 0) {
        const fitted = fitting ? this.map.fitTransform() : null;
        const centre1: Pt = fitted ? [(width / 2 - fitted.x) / fitted.k, (height / 2 - fitted.y) / fitted.k] : carried;
        const k1 = fitted ? fitted.k : start.k;
        const k = start.k * (k1 / start.k) ** e;
        const cx = lerp(centre0[0], centre1[0], e);
        const cy = lerp(centre0[1], centre1[1], e);
        this.map.jumpTo(width / 2 - cx * k, height / 2 - cy * k, k);
      }
      frames++;
      data.morphFrames = String(frames);
      if (t < 1) {
        this.animation = requestAnimationFrame(step);
        return;
      }
      this.animation = 0;
      this.morphRunning = false;
      this.mode = mode;
      data.mode = mode;
      data.transition = 'idle';
      this.host.morphEnded();
      this.map.settle();
    };
    this.animation = requestAnimationFrame(step);
  }
}
