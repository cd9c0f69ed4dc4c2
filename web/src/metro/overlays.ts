import { clustersPath, fetchClusters, fetchLayoutRoads, fetchVisualWorth, isAbort } from '../api/client';
import type { InterestParams } from '../api/interests';
import type { BBox, CitySummary, ClusterSpace, PoiCluster, VisualWorthRaster } from '../api/types';
import type { Box } from '../map/labels';
import type { Frame } from '../map/projection';
import type { SvgMap } from '../map/svg-map';
import { showAttribution } from '../ui/attribution';
import type { MapNotice } from '../ui/notice';
import { ClusterLayer, type ClusterPick } from './cluster-layer';
import { HeatLayer } from './heat-layer';
import { LatestRequest } from './latest-request';
import type { LayoutController, LayoutEntry } from './layout-controller';
import type { LayoutInfo } from './layout-info';
import type { Legend } from './legend';
import type { MapOptions } from './map-options';
import type { MetroLayers } from './metro-layers';
import type { Pt } from './morph';
import { RoadsLayer } from './roads-layer';

/** Clusters shown as markers (and as many more as dots). */
const CLUSTER_M = 10;
/** Quiet time after a pan or zoom before clusters and heat map are asked for. */
const REFRESH_DELAY_MS = 180;
/** The heat map's longest side, in raster cells. */
const HEAT_MAX_SIDE = 256;
/** The geographic heat map covers this much more than the window on each side, so a pan shows no edge at once. */
const HEAT_MARGIN = 0.15;

/**
 * The boxes (map pixels) of the panels over the map: the legend and info column's boxes, the
 * details, the zoom buttons, the attribution (empty or hidden ones left out). Cluster markers keep clear of them.
 */
function panelBoxes(mapElement: HTMLElement): Box[] {
  const area = mapElement.parentElement;
  if (!area) return [];
  const origin = mapElement.getBoundingClientRect();
  const panels = [...area.children].flatMap((child) =>
    child === mapElement ? [] : child.classList.contains('map-side') ? [...child.children] : [child]);
  return panels
    .map((panel) => panel.getBoundingClientRect())
    .filter((r) => r.width > 0 && r.height > 0)
    .map((r) => ({ x0: r.left - origin.left, y0: r.top - origin.top, x1: r.right - origin.left, y1: r.bottom - origin.top }));
}

const plural = (n: number, word: string) => `${n.toLocaleString()} ${word}${n === 1 ? '' : 's'}`;

/** The parts of the Metro view the overlays read and write. */
export interface OverlayParts {
  map: SvgMap;
  info: LayoutInfo;
  notice: MapNotice;
  options: MapOptions;
  legend: Legend;
  layout: LayoutController;
  attribution: HTMLElement;
  /** The `interests` parameter of the tourist's interests (undefined: none). */
  interests: () => string | undefined;
}

/** The city drawn, as the overlays need it. */
export interface OverlayCity {
  city: CitySummary;
  frame: Frame;
  layers: MetroLayers;
  /** The city's load: aborted when another city is drawn. */
  signal: AbortSignal;
  hasRoadNetwork: boolean;
  onPickCluster: (pick: ClusterPick) => void;
}

/**
 * What is drawn over the metro map for the window shown or the layout drawn: the clusters of
 * places, the visual worth heat map, and the streets under the octilinear layout (with their
 * data's credit). Asked for again when the map settles; hidden while a morph runs.
 *
 * The cluster layer reports data-status (off, loading, waiting, ready, error), data-query,
 * data-requests and data-latency-ms; the map element data-roads (loading, ready, none, off, error).
 */
export class MetroOverlays {
  private drawn?: OverlayCity;
  private clusters?: ClusterLayer;
  private heat?: HeatLayer;
  private roads?: RoadsLayer;
  /** Whether the city has a road network for its layout's streets (undefined: not asked yet). */
  private hasRoads?: boolean;
  private roadsRequest = 0;
  /** The data credits of the city drawn; the road network's join them while its streets are drawn. */
  private baseAttribution: string[] = [];
  private refreshTimer = 0;
  private readonly clusterRequest = new LatestRequest<{ space: ClusterSpace; answer: Awaited<ReturnType<typeof fetchClusters>> }>();
  private readonly heatRequest = new LatestRequest<VisualWorthRaster>();
  /** What the heat map shows: a window's raster or a layout's warped one (by key). */
  private heatShown?: string;
  private clusterAnswers = 0;

  constructor(private readonly parts: OverlayParts) {}

  /** A city is drawn: its layers get overlays. */
  attach(drawn: OverlayCity): void {
    const { map, options } = this.parts;
    const { layers } = drawn;
    this.drawn = drawn;
    this.heat = new HeatLayer(layers.heatLayer);
    this.roads = new RoadsLayer(map, layers.roadLayer, (shown) => this.creditRoads(shown));
    // Only a city with a road network has streets to ask for (no 404 to log otherwise).
    this.hasRoads = drawn.hasRoadNetwork ? undefined : false;
    options.setHasRoads(drawn.hasRoadNetwork);
    this.clusters = new ClusterLayer(map, layers.clusterLayer, drawn.onPickCluster, () => this.drawn?.layers.placeLabels());
    layers.setLabelObstacles(() => this.clusters?.boxes() ?? []);
    // Markers move off stations, lines and the server's station names.
    this.clusters.setObstacles(() => ({ ...layers.mapObstacles(), covered: panelBoxes(map.element) }));
  }

  /** The data credits of the city drawn. */
  setAttribution(credits: string[]): void {
    this.baseAttribution = credits;
    showAttribution(this.parts.attribution, credits);
  }

  /** No city drawn. */
  reset(): void {
    window.clearTimeout(this.refreshTimer);
    this.clusterRequest.cancel();
    this.heatRequest.cancel();
    this.heatShown = undefined;
    this.clusters?.destroy();
    this.clusters = undefined;
    this.heat = undefined;
    this.roads?.destroy();
    this.roads = undefined;
    this.roadsRequest++;
    this.drawn = undefined;
    this.setAttribution([]);
  }

  /** A morph starts: clusters, heat map and streets go until its end asks again. */
  pause(): void {
    window.clearTimeout(this.refreshTimer);
    this.clusterRequest.cancel();
    this.heatRequest.cancel();
    this.clusters?.clear();
    // Gone until the morph's end asks again: not "ready" meanwhile. A morph may now start
    // unasked (an improved layout swapped in), and whoever waits for the clusters of the
    // window (a test) must not take the cleared layer for them.
    const data = this.drawn?.layers.clusterLayer.dataset;
    if (data?.status === 'ready') data.status = 'waiting';
    this.heat?.clear();
    this.heatShown = undefined;
    this.parts.info.setPlaces(null);
    this.parts.info.setHeat(null);
    // The streets belong to one layout: off while the drawing moves.
    this.roads?.setVisible(false);
  }

  /** Asks for clusters and heat map after `delay` of quiet (a pan or zoom may go on). */
  schedule(delay = REFRESH_DELAY_MS): void {
    window.clearTimeout(this.refreshTimer);
    if (this.parts.layout.morphing) return; // the morph's end asks again
    this.refreshTimer = window.setTimeout(() => {
      this.refreshClusters();
      this.refreshHeat();
    }, delay);
  }

  // ---- The streets under the octilinear map ----

  /**
   * The streets warped into the layout drawn (GET /cities/{id}/layout/roads with its
   * parameters): asked for once per layout, the first time the octilinear map is drawn with the
   * switch on; shown while that map is drawn and the switch is on (RoadsLayer fades them in at
   * close zoom). A city without a road network (404) loses the switch.
   */
  updateRoads(): void {
    const { map, options, notice, layout: controller } = this.parts;
    const { roads: layer, drawn } = this;
    const layout = controller.shown;
    const data = map.element.dataset;
    const octilinear = controller.drawnMode === 'octilinear' && !controller.morphing && options.state.mode === 'octilinear';
    if (!layer || !drawn || !layout || !octilinear || !options.state.roads || this.hasRoads === false) {
      layer?.setVisible(false);
      if (layer) data.roads = this.hasRoads === false ? 'none' : 'off';
      return;
    }
    const { city } = drawn;
    const request = ++this.roadsRequest;
    data.roads = 'loading';
    const roads = (layout.roads ??= fetchLayoutRoads(city.id, layout.params, drawn.signal));
    roads.then(
      (answer) => {
        if (request !== this.roadsRequest || this.roads !== layer || controller.shown !== layout) return;
        if (!answer) {
          this.hasRoads = false;
          options.setHasRoads(false);
          layer.clear();
          data.roads = 'none';
          return;
        }
        this.hasRoads = true;
        notice.clear('roads');
        layer.show(answer, layout.placement);
        layer.setVisible(controller.drawnMode === 'octilinear' && !controller.morphing && options.state.roads);
        data.roads = 'ready';
      },
      (error: unknown) => {
        layout.roads = undefined;
        if (isAbort(error) || request !== this.roadsRequest || this.roads !== layer) return;
        data.roads = 'error';
        notice.error('roads', `Could not load the streets under the layout of ${city.name}`, error, () => this.updateRoads());
      },
    );
  }

  /** The road data's credit joins the attribution line while its streets are on screen. */
  private creditRoads(shown: boolean): void {
    const roads = this.roads?.roads;
    showAttribution(this.parts.attribution, shown && roads ? [...this.baseAttribution, ...roads.attribution] : this.baseAttribution);
  }

  // ---- Clusters and heat map, for the window shown ----

  /** The window in frame units: [x0, y0, x1, y1] (y down), or null when the map has no size. */
  private windowFrame(margin = 0): [Pt, Pt] | null {
    const { map } = this.parts;
    const { width, height } = map.size;
    if (width === 0 || height === 0) return null;
    const [x0, y0] = map.toFrame(-margin * width, -margin * height);
    const [x1, y1] = map.toFrame((1 + margin) * width, (1 + margin) * height);
    return [
      [x0, y0],
      [x1, y1],
    ];
  }

  private windowLonLat(frame: Frame, margin = 0): BBox | null {
    const window = this.windowFrame(margin);
    if (!window) return null;
    const [west, north] = frame.unproject(...window[0]);
    const [east, south] = frame.unproject(...window[1]);
    return [west, south, east, north];
  }

  refreshClusters(): void {
    const { info, notice, options, legend, layout: controller } = this.parts;
    const { drawn, clusters } = this;
    if (!drawn || !clusters || controller.morphing) return;
    const { city, frame } = drawn;
    const data = drawn.layers.clusterLayer.dataset;
    if (city.counts.pois === 0 || !legend.poisVisible || options.state.pois !== 'clusters') {
      this.clusterRequest.cancel();
      clusters.clear();
      data.status = 'off';
      info.setPlaces(null);
      return;
    }
    const window = this.windowFrame();
    if (!window) return;
    const layout = controller.drawnLayout;
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
      bbox = this.windowLonLat(frame)!;
      toFrame = (position) => frame.project(position);
    }
    const query = { space, bbox, m: CLUSTER_M, layout: layout?.params, interests: this.parts.interests() };
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
        notice.clear('clusters');
        const previews = answer.previews.length > 0 ? `, ${answer.previews.length} more as dots` : '';
        info.setPlaces(
          answer.active === 0
            ? 'No cluster of places fits in this window: zoom out or pan.'
            : `Places: the ${plural(answer.clusters.length, 'most prominent cluster')} of ${answer.active} in view${previews} (${space === 'geo' ? 'geographic' : 'layout'} space, ${Math.round(ms)} ms)`,
        );
      },
      (error) => {
        data.status = 'error';
        notice.error('clusters', 'Could not load the clusters of places', error, () => this.refreshClusters());
      },
    );
  }

  refreshHeat(): void {
    const { map, info, notice, options, layout: controller } = this.parts;
    const { drawn, heat } = this;
    if (!drawn || !heat || controller.morphing) return;
    const { city, frame } = drawn;
    if (!options.state.heat) {
      this.heatRequest.cancel();
      heat.clear();
      this.heatShown = undefined;
      info.setHeat(null);
      return;
    }
    const layout = controller.drawnLayout;
    if (layout) {
      info.setHeat('Warped into the layout through its 21 × 21 mesh: a coarse picture of where the visual worth went.');
      if (this.heatShown === layout.key) return;
      layout.heat ??= this.meshRaster(city, layout, frame);
      const request = controller.request;
      this.heatRequest.run(
        () => layout.heat!,
        (raster) => {
          if (request !== controller.request || controller.shown !== layout) return;
          heat.showWarped(raster, layout.layout, layout.placement, frame);
          this.heatShown = layout.key;
          notice.clear('heat');
        },
        (error) => {
          layout.heat = undefined;
          notice.error('heat', 'Could not load the visual worth heat map', error, () => this.refreshHeat());
        },
      );
      return;
    }
    const bbox = this.windowLonLat(frame, HEAT_MARGIN);
    const { width, height } = map.size;
    if (!bbox || width === 0) return;
    const scale = Math.min(1, HEAT_MAX_SIDE / ((1 + 2 * HEAT_MARGIN) * Math.max(width, height)));
    const cells = (pixels: number) => Math.max(1, Math.round((1 + 2 * HEAT_MARGIN) * pixels * scale));
    info.setHeat('Visual worth of the places of interest (eq. 5.1), for the window shown.');
    this.heatRequest.run(
      (signal) => fetchVisualWorth(city.id, bbox, cells(width), cells(height), signal, this.parts.interests()),
      (raster) => {
        heat.showRaster(raster, frame);
        this.heatShown = 'window';
        notice.clear('heat');
      },
      (error) => notice.error('heat', 'Could not load the visual worth heat map', error, () => this.refreshHeat()),
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
}
