import type { Box } from '../map/labels';
import {
  clustersPath,
  fetchCities,
  fetchCity,
  fetchClusters,
  fetchLayout,
  fetchMetro,
  fetchPois,
  fetchVisualWorth,
  isAbort,
  type LayoutAnswer,
} from '../api/client';
import type {
  BBox,
  CitySummary,
  ClusterSpace,
  LastImport,
  LayoutImprovedEvent,
  LayoutParams,
  PoiCluster,
  PoiCollection,
  StationFeature,
  VisualWorthRaster,
  XY,
} from '../api/types';
import { cityCategories, type InterestParams } from '../api/interests';
import { mapControls } from '../map/controls';
import { extendBBox } from '../map/bbox';
import { frameFor, type Frame } from '../map/projection';
import { SvgMap, type Insets } from '../map/svg-map';
import { ClusterLayer, type ClusterPick } from '../metro/cluster-layer';
import { poiDetails, stationDetails, type DetailsContext } from '../metro/details';
import { exportButton } from '../metro/export-button';
import { HeatLayer } from '../metro/heat-layer';
import { InterestsPanel } from '../metro/interests-panel';
import { WalkControl } from '../metro/walk-layer';
import { LatestRequest } from '../metro/latest-request';
import { geoGrid, layoutGeometry, Placement, serverLabels } from '../metro/layout-geometry';
import { LayoutInfo } from '../metro/layout-info';
import { Legend } from '../metro/legend';
import { MapOptions, type MapMode } from '../metro/map-options';
import { MetroLayers, type MetroPick, type ServerLabels } from '../metro/metro-layers';
import { fetchLayoutRoads, RoadsLayer, type LayoutRoadsResponse } from '../metro/roads-layer';
import { carry, easeInOutCubic, geometryBounds, Morph, type Geometry, type Pt } from '../metro/morph';
import { attributionBox, showAttribution } from '../ui/attribution';
import { DetailsPanel } from '../ui/details-panel';
import { h } from '../ui/dom';
import { MapNotice } from '../ui/notice';
import { ControlSheet } from '../ui/sheet';
import { StatusOverlay } from '../ui/status';
import type { View } from './view';

const NO_POIS: Pick<PoiCollection, 'features' | 'attribution'> = { features: [], attribution: [] };
/** Clusters shown as markers (and as many more as dots). */
const CLUSTER_M = 10;
/** Quiet time after a pan or zoom before clusters and heat map are asked for. */
const REFRESH_DELAY_MS = 180;
const MORPH_MS = 750;
/** The heat map's longest side, in raster cells. */
const HEAT_MAX_SIDE = 256;
/** The geographic heat map covers this much more than the window on each side, so a pan shows no edge at once. */
const HEAT_MARGIN = 0.15;
/** A click on a cluster zooms in this much around it. */
const CLUSTER_ZOOM = 2.5;

/** The layouts of a city by parameters: what the client asks for (see layoutFor). */
const layoutKey = (cityId: string, params: InterestParams) => `${cityId}|${params.lengths}|${params.solver}|${params.interests ?? ''}`;

const plural = (n: number, word: string) => `${n.toLocaleString()} ${word}${n === 1 ? '' : 's'}`;
const lerp = (a: number, b: number, t: number) => a + (b - a) * t;

function reducedMotion(): boolean {
  return window.matchMedia('(prefers-reduced-motion: reduce)').matches;
}

/** A layout ready to draw: the answer, where it goes on the map, and the two drawings it morphs between. */
interface LayoutEntry extends LayoutAnswer {
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

/**
 * The Metro view: a city picker and the city's metro network and POIs, drawn geographically or
 * as the transit-centric octilinear layout (morphing between the two), with the visual worth
 * heat map and the POIs as clusters of the window shown.
 *
 * The map element reports data-status (loading, ready, error) and data-city (drawn), data-mode
 * (geographic, octilinear: the drawing shown once a morph is over), data-transition (running,
 * idle), data-layout (loading, ready, error), data-layout-solver (the drawn layout's solver:
 * fast, mip), data-layout-swaps (improved layouts swapped in) and data-roads (the streets under
 * the layout: loading, ready, none (no road network), off, error) for tests.
 */
export class MetroView implements View {
  readonly element: HTMLElement;
  private readonly picker: HTMLSelectElement;
  private readonly summary: HTMLElement;
  private readonly map: SvgMap;
  private readonly legend: Legend;
  private readonly details: DetailsPanel;
  /** "Your interests" (issue 17): their `interests` parameter goes with every layout, cluster and heat map request. */
  private readonly interests: InterestsPanel;
  /** "Walk from the nearest station" in a POI's details, and the walk over the map. */
  private readonly walk: WalkControl;
  private readonly options: MapOptions;
  private readonly sheet: ControlSheet;
  private readonly info = new LayoutInfo();
  private readonly notice = new MapNotice();
  private readonly status = new StatusOverlay();
  private readonly attribution = attributionBox();
  private cities?: CitySummary[];
  /** The city the route asks for, and the one drawn. */
  private wanted?: string;
  private drawn?: string;
  private layers?: MetroLayers;
  private clusters?: ClusterLayer;
  private heat?: HeatLayer;
  private roads?: RoadsLayer;
  /** Whether the city has a road network for its layout's streets (undefined: not asked yet). */
  private hasRoads?: boolean;
  private roadsRequest = 0;
  /** The data credits of the city drawn; the road network's join them while its streets are drawn. */
  private baseAttribution: string[] = [];
  private frame?: Frame;
  private city?: CitySummary;
  private context?: DetailsContext;
  private cityLoad?: AbortController;
  /** Layouts of the drawn city by parameters, asked for or ready. */
  private readonly layouts = new Map<string, Promise<LayoutEntry>>();
  private readonly layoutsReady = new Set<string>();
  /** The layout drawn (octilinear) or last drawn (its mesh stays for the warp grid). */
  private shownLayout?: LayoutEntry;
  /** Counts mode and parameter changes: an answer for an older one is not drawn. */
  private modeRequest = 0;
  private animation = 0;
  private morphing = false;
  /** The drawing shown once the morph is over: what clusters and heat map are asked for. */
  private drawnMode: MapMode = 'geographic';
  private refreshTimer = 0;
  private readonly clusterRequest = new LatestRequest<{ space: ClusterSpace; answer: Awaited<ReturnType<typeof fetchClusters>> }>();
  private readonly heatRequest = new LatestRequest<VisualWorthRaster>();
  /** What the heat map shows: a window's raster or a layout's warped one (by key). */
  private heatShown?: string;
  private clusterAnswers = 0;

  constructor(private readonly go: (cityId: string, replace: boolean) => void) {
    this.picker = h('select', { id: 'city-picker', 'data-testid': 'city-picker', disabled: true });
    this.picker.addEventListener('change', () => this.go(this.picker.value, false));
    this.summary = h('p', { class: 'toolbar-summary', 'aria-live': 'polite' });

    this.map = new SvgMap('Metro map');
    this.map.element.dataset.testid = 'metro-map';
    this.map.element.dataset.mode = 'geographic';
    this.map.element.dataset.transition = 'idle';
    this.legend = new Legend({
      onHighlight: (lineId) => this.layers?.highlightLine(lineId),
      onPoisVisible: () => this.applyPoiMode(),
      onLabelsVisible: (visible) => this.layers?.setLabelsVisible(visible),
    });
    this.options = new MapOptions({
      onMode: (mode) => (mode === 'octilinear' ? void this.showOctilinear() : this.showGeographic()),
      onLayoutParams: () => {
        if (this.options.state.mode === 'octilinear') void this.showOctilinear();
      },
      onHeat: () => this.refreshHeat(),
      onGrid: (visible) => {
        this.layers?.setGridVisible(visible);
        this.describeGrid();
      },
      onRoads: () => this.updateRoads(),
      onPoiMode: () => this.applyPoiMode(),
    });
    this.details = new DetailsPanel(() => this.pick(null));
    this.interests = new InterestsPanel(() => this.interestsChanged());
    this.walk = new WalkControl(this.map, () => ({
      mode: this.morphing ? null : this.drawnMode,
      frame: this.frame,
      placement: this.drawnMode === 'octilinear' ? this.shownLayout?.placement : undefined,
      geometry: this.layers?.geometry,
    }));
    this.map.setFitInsets(() => this.overlayInsets());
    this.map.onSettle(() => this.scheduleRefresh());

    // The switches: a side panel on desktop, a bottom sheet on phones; the engineering ones
    // and the layout's numbers folded into Advanced.
    this.sheet = new ControlSheet(
      'metro',
      'Map options',
      {
        title: 'Metro map for sightseeing',
        text: 'See a city’s metro lines together with its sights. Tap a station or a pin for details; pinch or use + and − to zoom.',
        tryThis: 'switch Layout to “Schematic”: the map turns into a tidy metro diagram and the sights move along with it.',
      },
      'metro-side',
      [
        h('div', { class: 'field-row' }, h('label', { class: 'field', for: 'city-picker' }, 'City'), this.picker),
        this.summary,
        this.options.element,
        this.interests.element,
        this.legend.element,
        exportButton(() => (this.city ? { cityId: this.city.id, params: this.layoutParams() } : null)),
        h(
          'details',
          { class: 'advanced', 'data-testid': 'metro-advanced' },
          h('summary', {}, 'Advanced'),
          h('div', { class: 'advanced-body' }, this.options.advanced, this.info.element),
        ),
      ],
    );
    this.map.element.setAttribute('role', 'region');
    this.map.element.setAttribute('aria-label', 'Metro map: drag to pan, pinch or use + and − to zoom');
    this.element = h(
      'section',
      { class: 'view view-metro has-sheet' },
      this.sheet.element,
      h(
        'div',
        { class: 'map-area' },
        this.map.element,
        this.info.busy,
        this.details.element,
        mapControls(this.map),
        this.attribution,
        this.notice.element,
        this.status.element,
      ),
    );
    void this.loadCities();
  }

  show(cityId: string | undefined): void {
    this.wanted = cityId;
    if (this.cities) this.openWanted();
  }

  catalogChanged(lastImport: LastImport | undefined): void {
    const touchesDrawn = !lastImport || (lastImport.kind !== 'roads' && lastImport.target === this.drawn);
    void this.loadCities(touchesDrawn);
  }

  /** Fills the picker; `reload` draws the current city again (its data changed). */
  private async loadCities(reload = false): Promise<void> {
    if (!this.cities) this.status.loading('Loading cities…');
    try {
      this.cities = await fetchCities();
    } catch (error) {
      // A failed refresh keeps the list we have; only a first load has nothing to show.
      if (!this.cities) this.status.error('Could not load the list of cities', error, () => void this.loadCities());
      return;
    }
    this.fillPicker(this.cities);
    if (reload) this.drawn = undefined;
    this.openWanted();
  }

  private fillPicker(cities: CitySummary[]): void {
    this.picker.replaceChildren(
      ...cities.map((city) => h('option', { value: city.id }, `${city.name} — ${plural(city.counts.stations, 'station')}`)),
    );
    this.picker.disabled = cities.length === 0;
    if (this.wanted) this.picker.value = this.wanted;
  }

  private openWanted(): void {
    const cities = this.cities ?? [];
    if (!this.wanted) {
      if (cities[0]) this.go(cities[0].id, true);
      else this.status.error('No cities yet', new Error('Import a city with `tourmap import manifest` and it will appear here.'));
      return;
    }
    const city = cities.find((candidate) => candidate.id === this.wanted);
    if (!city) {
      this.cityLoad?.abort();
      this.drawn = undefined;
      this.clearMap();
      this.map.element.dataset.status = 'error';
      this.status.error(`There is no city “${this.wanted}”`, new Error('Pick one of the cities in the list.'));
      return;
    }
    this.picker.value = city.id;
    document.title = `${city.name} metro · tourmap`;
    if (this.drawn !== city.id) void this.loadCity(city);
  }

  private async loadCity(summary: CitySummary): Promise<void> {
    this.cityLoad?.abort();
    const load = new AbortController();
    this.cityLoad = load;
    this.drawn = summary.id;
    this.map.element.dataset.status = 'loading';
    this.status.loading(`Loading ${summary.name}…`);
    try {
      const [city, metro, pois] = await Promise.all([
        fetchCity(summary.id, load.signal),
        fetchMetro(summary.id, load.signal),
        summary.counts.pois > 0 ? fetchPois(summary.id, load.signal) : NO_POIS,
      ]);
      if (load.signal.aborted) return;
      this.clearMap();
      // Legend and attribution first: fitting the map keeps clear of them.
      this.legend.show(metro.lines, pois.features.length, city.poi_categories);
      this.interests.show(summary.id, cityCategories(city));
      this.baseAttribution = [...city.attribution, ...metro.attribution, ...pois.attribution];
      showAttribution(this.attribution, this.baseAttribution);
      const frame = frameFor(extendBBox(city.bbox, pois.features.map((poi) => poi.geometry.coordinates)));
      this.map.setFitBounds(null);
      this.map.setFrame(frame);
      this.frame = frame;
      this.city = summary;
      this.layers = new MetroLayers(this.map, frame, metro, pois.features, (pick) => this.pick(pick));
      this.heat = new HeatLayer(this.layers.heatLayer);
      this.roads = new RoadsLayer(this.map, this.layers.roadLayer, (drawn) => this.creditRoads(drawn));
      this.walk.setCity(summary.id, city.road_network !== null);
      // Only a city with a road network has streets to ask for (no 404 to log otherwise).
      this.hasRoads = city.road_network ? undefined : false;
      this.options.setHasRoads(city.road_network !== null);
      this.clusters = new ClusterLayer(
        this.map,
        this.layers.clusterLayer,
        (pick) => this.pickCluster(pick),
        () => this.layers?.placeLabels(),
      );
      this.layers.setLabelObstacles(() => this.clusters?.boxes() ?? []);
      // Markers move off stations, lines and the server's station names.
      this.clusters.setObstacles(() => ({ ...(this.layers?.mapObstacles() ?? { boxes: [], segments: [] }), covered: this.panelBoxes() }));
      this.layers.setLabelsVisible(this.legend.labelsVisible);
      this.layers.setGridVisible(this.options.state.grid);
      this.options.setHasPois(pois.features.length > 0);
      this.context = {
        lines: new Map(metro.lines.map((line) => [line.id, line])),
        stations: metro.features.filter((f): f is StationFeature => f.properties.kind === 'station'),
        pois: pois.features,
        onPick: (pick) => this.pick(pick, true),
        walk: (poi) => this.walk.panel(poi),
      };
      this.applyPoiMode();
      this.summary.textContent = [
        plural(city.counts.stations, 'station'),
        plural(metro.lines.length, 'line'),
        pois.features.length > 0 ? plural(pois.features.length, 'place') + ' of interest' : '',
      ].filter(Boolean).join(' · ');
      this.status.clear();
      this.map.element.dataset.city = city.id;
      this.map.element.dataset.status = 'ready';
      this.describeGrid();
      if (this.options.state.mode === 'octilinear') void this.showOctilinear();
      this.scheduleRefresh(0);
    } catch (error) {
      if (isAbort(error)) return;
      this.drawn = undefined;
      this.clearMap();
      this.map.element.dataset.status = 'error';
      this.status.error(`Could not load the metro map of ${summary.name}`, error, () => void this.loadCity(summary));
    }
  }

  /**
   * The boxes (map pixels) of the panels over the map: the legend and info column's boxes, the
   * details, the zoom buttons, the attribution (empty or hidden ones left out).
   */
  private panelBoxes(): Box[] {
    const area = this.map.element.parentElement;
    if (!area) return [];
    const origin = this.map.element.getBoundingClientRect();
    const panels = [...area.children].flatMap((child) =>
      child === this.map.element ? [] : child.classList.contains('map-side') ? [...child.children] : [child]);
    return panels
      .map((panel) => panel.getBoundingClientRect())
      .filter((r) => r.width > 0 && r.height > 0)
      .map((r) => ({ x0: r.left - origin.left, y0: r.top - origin.top, x1: r.right - origin.left, y1: r.bottom - origin.top }));
  }

  private clearMap(): void {
    cancelAnimationFrame(this.animation);
    window.clearTimeout(this.refreshTimer);
    this.morphing = false;
    this.drawnMode = 'geographic';
    this.modeRequest++;
    this.clusterRequest.cancel();
    this.heatRequest.cancel();
    this.heatShown = undefined;
    this.layouts.clear();
    this.layoutsReady.clear();
    this.shownLayout = undefined;
    this.clusters?.destroy();
    this.clusters = undefined;
    this.heat = undefined;
    this.roads?.destroy();
    this.roads = undefined;
    this.roadsRequest++;
    this.baseAttribution = [];
    this.layers?.destroy();
    this.layers = undefined;
    this.frame = undefined;
    this.city = undefined;
    this.context = undefined;
    this.details.hide();
    this.walk.setCity(undefined, false);
    this.interests.hide();
    this.legend.hide();
    this.info.hideLayout();
    this.info.setHeat(null);
    this.info.setPlaces(null);
    this.info.setGrid(null);
    this.notice.clear();
    this.summary.textContent = '';
    showAttribution(this.attribution, []);
    const data = this.map.element.dataset;
    delete data.city;
    delete data.layout;
    delete data.roads;
    data.mode = 'geographic';
    data.transition = 'idle';
  }

  /** The attribution covers the map's foot: fit the network above it. */
  private overlayInsets(): Insets {
    return { top: 0, right: 0, bottom: this.attribution.offsetHeight, left: 0 };
  }

  // ---- Geographic <-> octilinear ----

  private layoutParams(): InterestParams {
    const interests = this.interests.query;
    return { lengths: this.options.state.lengths, solver: this.options.state.solver, ...(interests ? { interests } : {}) };
  }

  /** New interests: the schematic morphs to their layout; clusters and heat map follow them. */
  private interestsChanged(): void {
    if (!this.city) return;
    if (this.options.state.mode === 'octilinear') void this.showOctilinear();
    else this.scheduleRefresh(0);
  }

  /** The layout for the parameters, asked for once per city and parameters (a failure is forgotten). */
  private layoutFor(city: CitySummary, params: LayoutParams, signal: AbortSignal): Promise<LayoutEntry> {
    const key = layoutKey(city.id, params);
    let entry = this.layouts.get(key);
    if (!entry) {
      const layers = this.layers!;
      const frame = this.frame!;
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

  private async showOctilinear(): Promise<void> {
    const city = this.city;
    const layers = this.layers;
    const load = this.cityLoad;
    if (!city || !layers || !load) return;
    const request = ++this.modeRequest;
    const params = this.layoutParams();
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
      entry = await this.layoutFor(city, params, load.signal);
    } catch (error) {
      if (isAbort(error) || request !== this.modeRequest || this.layers !== layers) return;
      data.layout = 'error';
      // The layout drawn stays, and the switches say which one it is.
      if (this.shownLayout && this.drawnMode === 'octilinear') {
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
      if (this.drawnMode !== 'octilinear') this.options.setMode('geographic');
      return;
    }
    if (request !== this.modeRequest || this.layers !== layers) return;
    this.notice.clear('layout');
    this.shownLayout = entry;
    data.layout = 'ready';
    data.layoutSolver = entry.layout.solver.kind;
    this.info.showLayout(entry);
    this.morphTo(entry.geometry, 'octilinear', entry.labels);
  }

  /**
   * The server improved a default layout in the background (fewer bends, room for names). If it is
   * one this view asked for (same city version and parameters), the cached answer is dropped;
   * if it is the one drawn, the improved one is fetched and morphed in like any layout change:
   * no reload, and the view stays where the user put it (a fitted map stays fitted).
   */
  layoutImproved(event: LayoutImprovedEvent): void {
    const city = this.city;
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
    const stillAsked = this.city === city && this.layouts.get(key) === asked;
    if (!stillAsked || old.layout.version !== event.version || !sameParams) return;
    if (old.layout.solver.improvement === 'applied') return; // asked for after the improvement
    this.layouts.delete(key);
    this.layoutsReady.delete(key);
    const load = this.cityLoad;
    if (!load) return;
    let entry: LayoutEntry;
    try {
      entry = await this.layoutFor(city, params, load.signal);
    } catch {
      return; // the layout drawn stays; a later switch asks again
    }
    // Swapped in only where the old one is still what is drawn, or being morphed to.
    const current = this.layoutParams();
    const drawn = this.shownLayout === old && this.options.state.mode === 'octilinear';
    if (!drawn || current.lengths !== params.lengths || current.solver !== 'auto') return;
    const data = this.map.element.dataset;
    this.shownLayout = entry;
    data.layoutSolver = entry.layout.solver.kind;
    data.layoutSwaps = String(Number(data.layoutSwaps ?? 0) + 1);
    this.info.showLayout(entry);
    this.morphTo(entry.geometry, 'octilinear', entry.labels);
  }

  private showGeographic(): void {
    this.modeRequest++;
    const layers = this.layers;
    this.info.hideLayout();
    if (this.map.element.dataset.layout === 'loading') delete this.map.element.dataset.layout;
    if (!layers) return;
    this.morphTo(this.shownLayout?.geoGeometry ?? layers.geo, 'geographic', null);
  }

  /**
   * Morphs from what is drawn (even halfway through another morph) to `target`, eased, while the
   * view follows: a fitted map is fitted to the target, otherwise the place at the centre of the
   * window stays there (carried by the nearby stations' moves). Clusters and heat map are hidden
   * meanwhile and asked for again at the end.
   */
  private morphTo(target: Geometry, mode: MapMode, labels: ServerLabels | null): void {
    const layers = this.layers;
    if (!layers) return;
    // The octilinear layout comes with the server's station names; the geographic map places its own.
    layers.setServerLabels(labels);
    cancelAnimationFrame(this.animation);
    window.clearTimeout(this.refreshTimer);
    this.clusterRequest.cancel();
    this.heatRequest.cancel();
    this.clusters?.clear();
    // Gone until the morph's end asks again: not "ready" meanwhile. A morph may now start
    // unasked (an improved layout swapped in), and whoever waits for the clusters of the
    // window (a test) must not take the cleared layer for them.
    if (layers.clusterLayer.dataset.status === 'ready') layers.clusterLayer.dataset.status = 'waiting';
    this.heat?.clear();
    this.heatShown = undefined;
    this.info.setPlaces(null);
    this.info.setHeat(null);
    // The streets belong to one layout: off while the drawing moves.
    this.roads?.setVisible(false);

    const from = layers.geometry;
    const morph = new Morph(from, target);
    this.map.setFitBounds(mode === 'octilinear' ? geometryBounds(target) : null);
    const { width, height } = this.map.size;
    const start = this.map.view;
    const fitted = this.map.followingFit ? this.map.fitTransform() : null;
    const centre0 = this.map.toFrame(width / 2, height / 2);
    // A fitted map ends fitted; otherwise the centre goes where the stations around it go.
    const centre1: Pt = fitted ? [(width / 2 - fitted.x) / fitted.k, (height / 2 - fitted.y) / fitted.k] : carry(centre0, from.stations, target.stations);
    const k1 = fitted ? fitted.k : start.k;
    const gestures = this.map.gestureCount;
    const duration = reducedMotion() ? 0 : MORPH_MS;
    const data = this.map.element.dataset;
    this.morphing = true;
    this.walk.redraw(); // hidden while the map moves
    data.transition = 'running';
    data.morphTo = mode;
    const started = performance.now();
    let frames = 0;

    const step = (now: number) => {
      const t = duration > 0 ? Math.min(1, (now - started) / duration) : 1;
      const e = easeInOutCubic(t);
      layers.setGeometry(morph.at(e), t >= 1);
      // The user's own pan or zoom meanwhile wins over the view's move.
      if (this.map.gestureCount === gestures && width > 0 && height > 0) {
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
      this.morphing = false;
      this.drawnMode = mode;
      data.mode = mode;
      data.transition = 'idle';
      this.walk.redraw();
      this.describeGrid();
      this.updateRoads();
      this.map.settle();
    };
    this.animation = requestAnimationFrame(step);
  }

  /** Says what the warp grid shows, or why there is none. */
  private describeGrid(): void {
    if (!this.options.state.grid || !this.layers) {
      this.info.setGrid(null);
      return;
    }
    this.info.setGrid(
      !this.shownLayout
        ? 'Warp grid: it comes with the octilinear layout. Switch to Octilinear.'
        : this.drawnMode === 'octilinear'
          ? 'Warp grid: a regular 21 × 21 mesh and the network’s outline, warped with the layout: where cells grew, space went to places worth seeing.'
          : 'Warp grid: the regular mesh (and the network’s outline) that the octilinear layout warps.',
    );
  }

  // ---- The streets under the octilinear map ----

  /**
   * The streets warped into the layout drawn (GET /cities/{id}/layout/roads with its
   * parameters): asked for once per layout, the first time the octilinear map is drawn with the
   * switch on; shown while that map is drawn and the switch is on (RoadsLayer fades them in at
   * close zoom). A city without a road network (404) loses the switch.
   */
  private updateRoads(): void {
    const { roads: layer, city, shownLayout: layout } = this;
    const data = this.map.element.dataset;
    const octilinear = this.drawnMode === 'octilinear' && !this.morphing && this.options.state.mode === 'octilinear';
    if (!layer || !city || !layout || !octilinear || !this.options.state.roads || this.hasRoads === false) {
      layer?.setVisible(false);
      if (layer) data.roads = this.hasRoads === false ? 'none' : 'off';
      return;
    }
    const request = ++this.roadsRequest;
    data.roads = 'loading';
    layout.roads ??= fetchLayoutRoads(city.id, layout.params, this.cityLoad?.signal);
    layout.roads.then(
      (answer) => {
        if (request !== this.roadsRequest || this.roads !== layer || this.shownLayout !== layout) return;
        if (!answer) {
          this.hasRoads = false;
          this.options.setHasRoads(false);
          layer.clear();
          data.roads = 'none';
          return;
        }
        this.hasRoads = true;
        this.notice.clear('roads');
        layer.show(answer, layout.placement);
        layer.setVisible(this.drawnMode === 'octilinear' && !this.morphing && this.options.state.roads);
        data.roads = 'ready';
      },
      (error: unknown) => {
        layout.roads = undefined;
        if (isAbort(error) || request !== this.roadsRequest || this.roads !== layer) return;
        data.roads = 'error';
        this.notice.error('roads', `Could not load the streets under the layout of ${city.name}`, error, () => this.updateRoads());
      },
    );
  }

  /** The road data's credit joins the attribution line while its streets are on screen. */
  private creditRoads(drawn: boolean): void {
    const roads = this.roads?.roads;
    showAttribution(this.attribution, drawn && roads ? [...this.baseAttribution, ...roads.attribution] : this.baseAttribution);
  }

  // ---- Clusters and heat map, for the window shown ----

  private scheduleRefresh(delay = REFRESH_DELAY_MS): void {
    window.clearTimeout(this.refreshTimer);
    if (this.morphing) return; // the morph's end asks again
    this.refreshTimer = window.setTimeout(() => {
      this.refreshClusters();
      this.refreshHeat();
    }, delay);
  }

  /** The window in frame units: [x0, y0, x1, y1] (y down), or null when the map has no size. */
  private windowFrame(margin = 0): [Pt, Pt] | null {
    const { width, height } = this.map.size;
    if (width === 0 || height === 0) return null;
    const [x0, y0] = this.map.toFrame(-margin * width, -margin * height);
    const [x1, y1] = this.map.toFrame((1 + margin) * width, (1 + margin) * height);
    return [
      [x0, y0],
      [x1, y1],
    ];
  }

  private windowLonLat(margin = 0): BBox | null {
    const window = this.windowFrame(margin);
    if (!window || !this.frame) return null;
    const [west, north] = this.frame.unproject(...window[0]);
    const [east, south] = this.frame.unproject(...window[1]);
    return [west, south, east, north];
  }

  private applyPoiMode(): void {
    const clustered = this.options.state.pois === 'clusters';
    this.layers?.setPoisVisible(this.legend.poisVisible, clustered);
    this.refreshClusters();
  }

  private refreshClusters(): void {
    const { city, clusters, frame } = this;
    const data = clusters ? this.layers?.clusterLayer.dataset : undefined;
    if (!city || !clusters || !frame || !data || this.morphing) return;
    if (city.counts.pois === 0 || !this.legend.poisVisible || this.options.state.pois !== 'clusters') {
      this.clusterRequest.cancel();
      clusters.clear();
      data.status = 'off';
      this.info.setPlaces(null);
      return;
    }
    const window = this.windowFrame();
    if (!window) return;
    const layout = this.drawnMode === 'octilinear' ? this.shownLayout : undefined;
    const space: ClusterSpace = layout ? 'layout' : 'geo';
    let bbox: [number, number, number, number];
    let toFrame: (position: [number, number]) => Pt;
    // In layout space the API gives the cluster's centre as its representative's position: the
    // layout's own POI positions say where the representative is.
    const representativeAt = (cluster: PoiCluster) => layout?.poiPositions.get(cluster.representative.id);
    if (layout) {
      const [ax, ay] = layout.placement.fromFrame(window[0]);
      const [bx, by] = layout.placement.fromFrame(window[1]);
      bbox = [Math.min(ax, bx), Math.min(ay, by), Math.max(ax, bx), Math.max(ay, by)];
      toFrame = (position) => layout.placement.toFrame(position);
    } else {
      bbox = this.windowLonLat()!;
      toFrame = (position) => frame.project(position);
    }
    const query = { space, bbox, m: CLUSTER_M, layout: layout?.params, interests: this.interests.query };
    data.status = 'loading';
    const started = performance.now();
    this.clusterRequest.run(
      (signal) => fetchClusters(city.id, query, signal).then((answer) => ({ space, answer })),
      ({ answer }) => {
        // The request the markers answer (tests ask the API the same).
        data.query = clustersPath(city.id, query);
        const ms = performance.now() - started;
        clusters.show(answer, space, toFrame, representativeAt);
        this.clusterAnswers++;
        data.status = 'ready';
        data.requests = String(this.clusterAnswers);
        data.latencyMs = ms.toFixed(1);
        this.notice.clear('clusters');
        const previews = answer.previews.length > 0 ? `, ${answer.previews.length} more as dots` : '';
        this.info.setPlaces(
          answer.active === 0
            ? 'No cluster of places fits in this window: zoom out or pan.'
            : `Places: the ${plural(answer.clusters.length, 'most prominent cluster')} of ${answer.active} in view${previews} (${space === 'geo' ? 'geographic' : 'layout'} space, ${Math.round(ms)} ms)`,
        );
      },
      (error) => {
        data.status = 'error';
        this.notice.error('clusters', 'Could not load the clusters of places', error, () => this.refreshClusters());
      },
    );
  }

  private refreshHeat(): void {
    const { city, heat, frame } = this;
    if (!city || !heat || !frame || this.morphing) return;
    if (!this.options.state.heat) {
      this.heatRequest.cancel();
      heat.clear();
      this.heatShown = undefined;
      this.info.setHeat(null);
      return;
    }
    const layout = this.drawnMode === 'octilinear' ? this.shownLayout : undefined;
    if (layout) {
      this.info.setHeat("Warped into the layout through its 21 × 21 mesh: a coarse picture of where the visual worth went.");
      if (this.heatShown === layout.key) return;
      layout.heat ??= this.meshRaster(city, layout, frame);
      const request = this.modeRequest;
      this.heatRequest.run(
        () => layout.heat!,
        (raster) => {
          if (request !== this.modeRequest || this.shownLayout !== layout) return;
          heat.showWarped(raster, layout.layout, layout.placement, frame);
          this.heatShown = layout.key;
          this.notice.clear('heat');
        },
        (error) => {
          layout.heat = undefined;
          this.notice.error('heat', 'Could not load the visual worth heat map', error, () => this.refreshHeat());
        },
      );
      return;
    }
    const bbox = this.windowLonLat(HEAT_MARGIN);
    const { width, height } = this.map.size;
    if (!bbox || width === 0) return;
    const scale = Math.min(1, HEAT_MAX_SIDE / ((1 + 2 * HEAT_MARGIN) * Math.max(width, height)));
    const cells = (pixels: number) => Math.max(1, Math.round((1 + 2 * HEAT_MARGIN) * pixels * scale));
    this.info.setHeat('Visual worth of the places of interest (eq. 5.1), for the window shown.');
    this.heatRequest.run(
      (signal) => fetchVisualWorth(city.id, bbox, cells(width), cells(height), signal, this.interests.query),
      (raster) => {
        heat.showRaster(raster, frame);
        this.heatShown = 'window';
        this.notice.clear('heat');
      },
      (error) => this.notice.error('heat', 'Could not load the visual worth heat map', error, () => this.refreshHeat()),
    );
  }

  /** A raster of the lon/lat box around the layout's geographic mesh, for warping. */
  private meshRaster(city: CitySummary, layout: LayoutEntry, frame: Frame): Promise<VisualWorthRaster> {
    const positions = layout.layout.mesh.geo.map((p) => frame.unproject(...layout.placement.toFrame(p)));
    const lons = positions.map(([lon]) => lon);
    const lats = positions.map(([, lat]) => lat);
    const bbox: BBox = [Math.min(...lons), Math.min(...lats), Math.max(...lons), Math.max(...lats)];
    const [x0, y0] = frame.project([bbox[0], bbox[3]]);
    const [x1, y1] = frame.project([bbox[2], bbox[1]]);
    const scale = HEAT_MAX_SIDE / Math.max(x1 - x0, y1 - y0);
    const width = Math.max(1, Math.round((x1 - x0) * scale));
    const height = Math.max(1, Math.round((y1 - y0) * scale));
    return fetchVisualWorth(city.id, bbox, width, height, undefined, (layout.params as InterestParams).interests);
  }

  // ---- Picks ----

  /** A cluster marker: its representative's details, and a zoom into the cluster. */
  private pickCluster(pick: ClusterPick): void {
    this.walk.clear();
    const context = this.context;
    if (!context) return;
    const { cluster } = pick;
    const poi = context.pois.find((candidate) => candidate.properties.id === cluster.representative.id);
    this.layers?.select(poi ? { kind: 'poi', poi } : null);
    const intro =
      cluster.size > 1
        ? h('p', { class: 'cluster-summary' }, `The most prominent of ${plural(cluster.size, 'place')} in this cluster.`)
        : null;
    const zoom = cluster.size > 1 ? h('button', { type: 'button', class: 'button button-quiet cluster-zoom' }, 'Zoom in on the cluster') : null;
    zoom?.addEventListener('click', () => this.map.zoomTo(pick.center[0], pick.center[1], CLUSTER_ZOOM));
    const body = poi ? poiDetails(poi, context) : [h('p', { class: 'details-kind' }, cluster.representative.category)];
    this.details.show(cluster.representative.name, [intro, zoom, ...body].filter((node): node is HTMLElement => node !== null));
    if (cluster.size > 1) this.map.zoomTo(pick.center[0], pick.center[1], CLUSTER_ZOOM);
  }

  /** Shows a picked station or POI; `reveal` also moves the map to it (picked from a list). */
  private pick(pick: MetroPick | null, reveal = false): void {
    this.walk.clear();
    this.layers?.select(pick);
    if (!pick || !this.context) {
      this.details.hide();
      return;
    }
    if (reveal) this.layers?.reveal(pick);
    if (pick.kind === 'station') this.details.show(pick.station.properties.name, stationDetails(pick.station, this.context));
    else this.details.show(pick.poi.properties.name, poiDetails(pick.poi, this.context));
  }
}
