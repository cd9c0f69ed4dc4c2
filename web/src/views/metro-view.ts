import { fetchCities, fetchCity, fetchMetro, fetchPois, isAbort } from '../api/client';
import type { CitySummary, LastImport, LayoutImprovedEvent, PoiCollection, StationFeature } from '../api/types';
import { cityCategories, type InterestParams } from '../api/interests';
import { mapControls } from '../map/controls';
import { extendBBox } from '../map/bbox';
import { frameFor, type Frame } from '../map/projection';
import { SvgMap, type Insets } from '../map/svg-map';
import type { ClusterPick } from '../metro/cluster-layer';
import { poiDetails, stationDetails, type DetailsContext } from '../metro/details';
import { exportButton } from '../metro/export-button';
import { InterestsPanel } from '../metro/interests-panel';
import { WalkControl } from '../metro/walk-layer';
import { LayoutController } from '../metro/layout-controller';
import { LayoutInfo } from '../metro/layout-info';
import { Legend } from '../metro/legend';
import { MapOptions } from '../metro/map-options';
import { MetroLayers, type MetroPick } from '../metro/metro-layers';
import { MetroOverlays } from '../metro/overlays';
import { attributionBox } from '../ui/attribution';
import { DetailsPanel } from '../ui/details-panel';
import { h } from '../ui/dom';
import { MapNotice } from '../ui/notice';
import { ControlSheet } from '../ui/sheet';
import { StatusOverlay } from '../ui/status';
import { WantedPicker } from '../ui/wanted-picker';
import type { View } from './view';

const NO_POIS: Pick<PoiCollection, 'features' | 'attribution'> = { features: [], attribution: [] };
/** A click on a cluster zooms in this much around it. */
const CLUSTER_ZOOM = 2.5;

const plural = (n: number, word: string) => `${n.toLocaleString()} ${word}${n === 1 ? '' : 's'}`;

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
  private readonly picker: WantedPicker<CitySummary>;
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
  /** Geographic <-> octilinear: the layouts and the morph. */
  private readonly layout: LayoutController;
  /** Clusters, heat map and streets over the map. */
  private readonly overlays: MetroOverlays;
  private readonly info = new LayoutInfo();
  private readonly notice = new MapNotice();
  private readonly status = new StatusOverlay();
  private readonly attribution = attributionBox();
  /** The city drawn (or being loaded). */
  private drawn?: string;
  private layers?: MetroLayers;
  private frame?: Frame;
  private city?: CitySummary;
  private context?: DetailsContext;
  private cityLoad?: AbortController;

  constructor(private readonly go: (cityId: string, replace: boolean) => void) {
    this.picker = new WantedPicker<CitySummary>({
      id: 'city-picker',
      label: (city) => `${city.name} — ${plural(city.counts.stations, 'station')}`,
      go: (id, replace) => this.go(id, replace),
      open: (city) => {
        document.title = `${city.name} metro · tourmap`;
        if (this.drawn !== city.id) void this.loadCity(city);
      },
      missing: (id) => {
        this.cityLoad?.abort();
        this.drawn = undefined;
        this.clearMap();
        this.map.element.dataset.status = 'error';
        this.status.error(`There is no city “${id}”`, new Error('Pick one of the cities in the list.'));
      },
      empty: () => this.status.error('No cities yet', new Error('Import a city with `tourmap import manifest` and it will appear here.')),
    });
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
      onMode: (mode) => (mode === 'octilinear' ? void this.layout.showOctilinear() : this.layout.showGeographic()),
      onLayoutParams: () => {
        if (this.options.state.mode === 'octilinear') void this.layout.showOctilinear();
      },
      onHeat: () => this.overlays.refreshHeat(),
      onGrid: (visible) => {
        this.layers?.setGridVisible(visible);
        this.describeGrid();
      },
      onRoads: () => this.overlays.updateRoads(),
      onPoiMode: () => this.applyPoiMode(),
    });
    this.details = new DetailsPanel(() => this.pick(null));
    this.interests = new InterestsPanel(() => this.interestsChanged());
    this.layout = new LayoutController(this.map, this.info, this.notice, this.options, {
      city: () => this.city,
      layers: () => this.layers,
      frame: () => this.frame,
      signal: () => this.cityLoad?.signal,
      params: () => this.layoutParams(),
      morphStarted: () => {
        this.overlays.pause();
        this.walk.redraw(); // hidden while the map moves
      },
      morphEnded: () => {
        this.walk.redraw();
        this.describeGrid();
        this.overlays.updateRoads();
      },
    });
    this.overlays = new MetroOverlays({
      map: this.map,
      info: this.info,
      notice: this.notice,
      options: this.options,
      legend: this.legend,
      layout: this.layout,
      attribution: this.attribution,
      interests: () => this.interests.query,
    });
    this.walk = new WalkControl(this.map, () => ({
      mode: this.layout.morphing ? null : this.layout.drawnMode,
      frame: this.frame,
      placement: this.layout.drawnLayout?.placement,
      geometry: this.layers?.geometry,
    }));
    this.map.setFitInsets(() => this.overlayInsets());
    this.map.onSettle(() => this.overlays.schedule());

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
        h('div', { class: 'field-row' }, h('label', { class: 'field', for: 'city-picker' }, 'City'), this.picker.element),
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
    this.picker.want(cityId);
  }

  catalogChanged(lastImport: LastImport | undefined): void {
    const touchesDrawn = !lastImport || (lastImport.kind !== 'roads' && lastImport.target === this.drawn);
    void this.loadCities(touchesDrawn);
  }

  layoutImproved(event: LayoutImprovedEvent): void {
    this.layout.layoutImproved(event);
  }

  /** Fills the picker; `reload` draws the current city again (its data changed). */
  private async loadCities(reload = false): Promise<void> {
    const loaded = this.picker.items !== undefined;
    if (!loaded) this.status.loading('Loading cities…');
    let cities: CitySummary[];
    try {
      cities = await fetchCities();
    } catch (error) {
      // A failed refresh keeps the list we have; only a first load has nothing to show.
      if (!loaded) this.status.error('Could not load the list of cities', error, () => void this.loadCities());
      return;
    }
    this.picker.setItems(cities, false);
    if (reload) this.drawn = undefined;
    this.picker.openWanted();
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
      this.overlays.setAttribution([...city.attribution, ...metro.attribution, ...pois.attribution]);
      const frame = frameFor(extendBBox(city.bbox, pois.features.map((poi) => poi.geometry.coordinates)));
      this.map.setFitBounds(null);
      this.map.setFrame(frame);
      this.frame = frame;
      this.city = summary;
      const layers = new MetroLayers(this.map, frame, metro, pois.features, (pick) => this.pick(pick));
      this.layers = layers;
      this.walk.setCity(summary.id, city.road_network !== null);
      this.overlays.attach({
        city: summary,
        frame,
        layers,
        signal: load.signal,
        hasRoadNetwork: city.road_network !== null,
        onPickCluster: (pick) => this.pickCluster(pick),
      });
      layers.setLabelsVisible(this.legend.labelsVisible);
      layers.setGridVisible(this.options.state.grid);
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
      if (this.options.state.mode === 'octilinear') void this.layout.showOctilinear();
      this.overlays.schedule(0);
    } catch (error) {
      if (isAbort(error)) return;
      this.drawn = undefined;
      this.clearMap();
      this.map.element.dataset.status = 'error';
      this.status.error(`Could not load the metro map of ${summary.name}`, error, () => void this.loadCity(summary));
    }
  }

  private clearMap(): void {
    this.layout.reset();
    this.overlays.reset();
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

  private layoutParams(): InterestParams {
    const interests = this.interests.query;
    return { lengths: this.options.state.lengths, solver: this.options.state.solver, ...(interests ? { interests } : {}) };
  }

  /** New interests: the schematic morphs to their layout; clusters and heat map follow them. */
  private interestsChanged(): void {
    if (!this.city) return;
    if (this.options.state.mode === 'octilinear') void this.layout.showOctilinear();
    else this.overlays.schedule(0);
  }

  private applyPoiMode(): void {
    const clustered = this.options.state.pois === 'clusters';
    this.layers?.setPoisVisible(this.legend.poisVisible, clustered);
    this.overlays.refreshClusters();
  }

  /** Says what the warp grid shows, or why there is none. */
  private describeGrid(): void {
    if (!this.options.state.grid || !this.layers) {
      this.info.setGrid(null);
      return;
    }
    this.info.setGrid(
      !this.layout.shown
        ? 'Warp grid: it comes with the octilinear layout. Switch to Octilinear.'
        : this.layout.drawnMode === 'octilinear'
          ? 'Warp grid: a regular 21 × 21 mesh and the network’s outline, warped with the layout: where cells grew, space went to places worth seeing.'
          : 'Warp grid: the regular mesh (and the network’s outline) that the octilinear layout warps.',
    );
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
