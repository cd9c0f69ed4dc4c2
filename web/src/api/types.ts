// Shapes of the tourmap API v1 responses (api/openapi.yaml), as far as the client reads them.

export type LonLat = [lon: number, lat: number];
/** [min_lon, min_lat, max_lon, max_lat] */
export type BBox = [number, number, number, number];

export interface CityCounts {
  stations: number;
  edges: number;
  lines: number;
  pois: number;
}

export interface CitySummary {
  id: string;
  name: string;
  bbox: BBox;
  center: LonLat;
  counts: CityCounts;
  version: number;
  attribution: string[];
}

export interface MetroLine {
  id: string;
  label: string;
  /** "rrggbb" without '#', may be empty */
  color: string;
  /**
   * How to tell it from a line of nearly its colour on the same map: a thin contrasting
   * border, and/or a dash pattern in stroke widths (empty: solid). Absent: plain.
   */
  style?: { casing: boolean; dash: number[] };
}

export interface CityDetail extends CitySummary {
  lines: MetroLine[];
  poi_categories: string[];
  /** The road network its streets under the layout come from (GET .../layout/roads); null: none. */
  road_network: string | null;
}

export interface PointGeometry {
  type: 'Point';
  coordinates: LonLat;
}

export interface LineStringGeometry {
  type: 'LineString';
  coordinates: LonLat[];
}

export interface Feature<G, P> {
  type: 'Feature';
  id?: string | number;
  geometry: G;
  properties: P;
}

export interface StationProperties {
  kind: 'station';
  id: string;
  station_id: string;
  name: string;
  lines: string[];
}

export interface EdgeProperties {
  kind: 'edge';
  from: string;
  to: string;
  lines: string[];
}

export type StationFeature = Feature<PointGeometry, StationProperties>;
export type EdgeFeature = Feature<LineStringGeometry, EdgeProperties>;

export interface MetroCollection {
  type: 'FeatureCollection';
  features: (StationFeature | EdgeFeature)[];
  lines: MetroLine[];
  attribution: string[];
  version: number;
}

export interface PoiProperties {
  id: string;
  name: string;
  category: string;
  image?: string;
  url?: string;
  wikipedia?: string;
  rank: number | null;
  popularity: number | null;
}

export type PoiFeature = Feature<PointGeometry, PoiProperties>;

export interface PoiCollection {
  type: 'FeatureCollection';
  features: PoiFeature[];
  matched: number;
  returned: number;
  offset: number;
  attribution: string[];
  version: number;
}

export interface RoadNetworkSummary {
  id: string;
  name: string;
  bbox: BBox;
  counts: { nodes: number; ways: number; edges: number };
  version: number;
  attribution: string[];
}

export interface RoadProperties {
  way: number;
  highway: string;
  name?: string;
}

export type RoadFeature = Feature<LineStringGeometry, RoadProperties>;

export interface RoadCollection {
  type: 'FeatureCollection';
  features: RoadFeature[];
  edges: number;
  attribution: string[];
  version: number;
}

export interface LastImport {
  /** "metro", "pois" (target: a city id) or "roads" (target: a road network id) */
  kind: string;
  target: string;
}

/**
 * A background improvement (a MIP polish with fewer bends, or room made for station names)
 * won for a default (solver=auto) layout and replaced it in the server's cache: the same
 * request now gets the improved one.
 */
export interface LayoutImprovedEvent {
  type: 'layout_improved';
  city: string;
  /** The city's version (the layout's `version`). */
  version: number;
  /** The request's canonical parameters (the server's cache key). */
  key: string;
  /** The layout's `params`, with solver "auto". */
  params: Record<string, string | number>;
  solver: { kind: string; status: string; gap: number | null; label_room?: LabelRoom };
  quality: LayoutQuality;
}

/** Messages of the /api/v1/events WebSocket. */
export type ServerEvent =
  | { type: 'hello'; catalog_version: number; last_import?: LastImport }
  | { type: 'catalog'; catalog_version: number; last_import?: LastImport }
  | LayoutImprovedEvent
  | { type: 'pong' }
  | { type: 'error'; code: string; message: string };

/** GET /api/v1/roads/{id}?format=topology: nodes once each, ways as lists of node indices. */
/** GET /roads/{id}/context: what a deformed map draws under its roads (openapi.yaml). */
export interface RoadContext {
  network: string;
  version: number;
  attribution: string;
  points: number;
  /** rings: [lon, lat, lon, lat, ...] each, the outer one first */
  areas: { kind: string; rings: number[][] }[];
  lines: { kind: string; name?: string; tunnel?: boolean; points: number[] }[];
  places: { kind: string; name: string; rank: number; pos: [number, number] }[];
}

export interface RoadTopology {
  network: string;
  version: number;
  bbox: BBox;
  /** [lon, lat, lon, lat, ...], one pair per node */
  positions: number[];
  /** OSM node id per node */
  node_ids: number[];
  ways: { way: number; highway: string; name?: string; nodes: number[] }[];
  attribution: string[];
}

export type DeformKind = 'focus' | 'mental' | 'destination';

export type GridOption =
  | { kind: 'adaptive'; base: number; depth: number; c: number }
  | { kind: 'uniform'; n: number }
  | { kind: 'edges' };

export type FocusRegion = { center: LonLat; radius_m: number; scale: number } | { polygon: LonLat[]; scale: number };

export type Guide = { vertex: number; target: LonLat } | { point: LonLat; target: LonLat };

/** The parts of a deformation request every kind shares (DeformCommon in the API). */
export interface DeformCommon {
  roads: string;
  grid: GridOption;
  solver: 'cholesky' | 'cg';
  relax: boolean;
  output: { roads: 'positions' | 'geojson' | 'none'; grid: boolean };
  /** Points of the original map to answer where the deformation put them (mapped_points). */
  map_points?: LonLat[];
}

export type DeformBody = DeformCommon &
  (
    | { regions: FocusRegion[]; map_points?: LonLat[] }
    | { guides: Guide[] }
    | { route: number[]; sketch: LonLat[]; simplify_m: number }
  );

export interface DeformGrid {
  /** Corner vertex indices per quad, counter-clockwise. */
  quads: [number, number, number, number][];
  before: LonLat[];
  after: LonLat[];
  /** [grid vertex, coarse quad] */
  tjunctions: [number, number][];
}

export interface DeformStats {
  residue: number;
  residue_rest: number;
  method: string;
  solver: string;
  unknowns: number;
  quads: number;
  grid_edges: number;
  support_edges: number;
  iterations: number;
  converged: boolean;
  foldovers: number;
  crossings_added: number | null;
  cache: 'hit' | 'miss';
  assembly_ms: number;
  factor_ms: number;
  solve_ms: number;
  rhs_ms: number;
  place_ms: number;
  output_ms: number;
  total_ms: number;
  scaled_edges: number;
  guides: number;
  road_edges: number;
}

export interface DeformResponse {
  app: string;
  roads_id: string;
  /** [lon, lat, ...] per node: parsed from JSON, or decoded from the binary answer. */
  positions?: ArrayLike<number>;
  grid: DeformGrid | null;
  guides?: { vertex: number; from: LonLat; target: LonLat; to: LonLat }[];
  /** Where the request's map_points went, in their order. */
  mapped_points?: LonLat[];
  stats: DeformStats;
  attribution: string[];
}

// ---- Transit-centric tourist map (GET /cities/{id}/layout, /visual-worth, /clusters) ----

/** A point in a city's planar frame: metres in its transverse Mercator projection, x east, y north. */
export type XY = [x: number, y: number];

export type LayoutLengths = 'visual-worth' | 'uniform';
export type LayoutSolverKind = 'auto' | 'fast' | 'mip';

/** The query of GET /cities/{id}/layout that picks a layout (also passed to /clusters?space=layout). */
export interface LayoutParams {
  lengths: LayoutLengths;
  solver: LayoutSolverKind;
}

export interface LayoutStationProperties {
  id: string;
  name: string;
  station_id: string;
  lines: string[];
  /** Normalised 0..1 */
  worth: number;
  /** The station's geographic position in the frame. */
  geo: XY;
  lonlat: LonLat;
}

export interface LayoutEdgeProperties {
  from: string;
  to: string;
  lines: string[];
  /** The lines left to right as seen travelling along the coordinates. */
  line_order?: string[];
  /** The geographic track in the frame. */
  geo: XY[];
  min_length?: number;
}

export interface LayoutPoiProperties {
  id: string;
  name: string;
  category: string;
  image?: string;
  url?: string;
  wikipedia?: string;
  worth: number;
  /** Far beyond the network: its warped position means little. */
  outside: boolean;
  geo: XY;
  lonlat: LonLat;
}

export interface PlanarPoint {
  type: 'Point';
  coordinates: XY;
}

export interface PlanarLineString {
  type: 'LineString';
  coordinates: XY[];
}

export interface LayoutQuality {
  octilinear_share: number;
  bends: number;
  crossings: number;
  geo_crossings: number;
  /** crossing pairs of edges that do not cross geographically */
  added_crossings: number;
  order_violations: number;
  min_edge: number;
  mean_edge: number;
  mean_displacement: number;
  min_station_gap?: number | null;
  min_station_gap_ratio?: number | null;
  /** The figures of ../shared/tools/metro_compare.py: bends as a reader counts them (along
   *  lines between interchanges), displacement as a share of the geographic diagonal. */
  compare?: { bends: number; displacement: number; min_over_mean_edge: number; octilinear_share: number };
}

export interface LayoutSolver {
  kind: string;
  status: string;
  gap: number | null;
  /**
   * scheduled: a background improvement (MIP, room for names) runs for this layout (a
   * layout_improved event follows if it wins); none: nothing follows; applied: this is the
   * improved layout.
   */
  improvement?: 'scheduled' | 'none' | 'applied';
  /** With improvement "none" after a background improvement ran: what it tried, none of it kept. */
  tried?: { mip?: LayoutSolver['mip']; label_room?: LabelRoom };
  mip?: { accepted?: boolean; status?: string; reason?: string; time_ms?: number; gap?: number | null };
  /** Room the background improvement made for names left out at 75 px (metro/city_layout.hpp). */
  label_room?: LabelRoom;
}

export interface LabelRoom {
  status: 'not_needed' | 'kept' | 'no_gain' | 'no_time';
  /** Stations that asked for room in the first round. */
  rooms: number;
  /** Stations without a name at the first zoom with symbols 12 px across, before and after. */
  unnamed_before: number;
  unnamed_after: number;
  /** Rounds for all names left out at once, then tries for one name in one place; tries kept of either kind. */
  rounds: number;
  single_tries: number;
  kept: number;
}

/**
 * Station names placed by the server for a set of zooms (metro/station_labels.hpp). A label is
 * [station index into stations.features, x0, y0, x1, y1 (its box), text x, text y (the first
 * line's baseline), anchor ('s' start, 'm' middle, 'e' end), split (byte where a second line
 * begins; 0: one line), size (the type's px: font.size_px, or font.small_px for a name that fits
 * in no other way)], in px from the station's point, y down. A name set off from its symbol
 * in a crowded place has four more numbers: its leader, from (x, y) at the symbol's rim to
 * (x, y) at the name's box.
 */
export type LayoutLabel =
  | [number, number, number, number, number, number, number, 's' | 'm' | 'e', number, number]
  | [number, number, number, number, number, number, number, 's' | 'm' | 'e', number, number, number, number, number, number];

export interface LayoutLabels {
  font: { family: string; weight: string; size_px: number; line_px: number; small_px: number };
  /** A symbol's radius: share * the mean edge on screen, within [min_px, max_px]. */
  symbol: { share: number; min_px: number; max_px: number };
  line_spacing_px: number;
  mean_edge_m: number;
  scales: { mean_edge_px: number; px_per_m: number; symbol_px: number; unlabelled: number; leaders: number; small: number; labels: LayoutLabel[] }[];
}

export interface LayoutResponse {
  city: string;
  version: number;
  frame: {
    kind: string;
    description?: string;
    layout_units_per_metre?: number;
    projection: { kind: string; lat0: number; lon0: number; k0: number };
  };
  stations: { type: 'FeatureCollection'; features: Feature<PlanarPoint, LayoutStationProperties>[] };
  edges: { type: 'FeatureCollection'; features: Feature<PlanarLineString, LayoutEdgeProperties>[] };
  pois: { type: 'FeatureCollection'; features: Feature<PlanarPoint, LayoutPoiProperties>[] };
  /** Row-major from the south-west corner, rows going north. */
  mesh: { cols: number; rows: number; geo: XY[]; layout: XY[] };
  /** One ring each (the network's convex hull), not closed. */
  outline: { geo: XY[]; layout: XY[] };
  lines: MetroLine[];
  quality: LayoutQuality;
  solver: LayoutSolver;
  labels?: LayoutLabels;
  timing_ms: { visual_worth?: number; layout?: number; warp?: number; total?: number };
  params: Record<string, string | number>;
  attribution: string[];
}

/** GET /cities/{id}/visual-worth: a raster of eq. 5.1 for a heat map. */
export interface VisualWorthRaster {
  bbox: BBox;
  width: number;
  height: number;
  /** Row-major from the north-west corner, normalised 0..1 */
  values: number[];
  max: number;
  stations: { id: string; worth: number }[];
}

export interface ClusterRepresentative {
  id: string;
  name: string;
  category: string;
  image?: string;
  url?: string;
  wikipedia?: string;
  /** lon/lat (space=geo) or [x, y] in the layout frame (space=layout) */
  position: [number, number];
}

export interface PoiCluster {
  id: string;
  /** lon/lat (space=geo) or [x, y] in the layout frame (space=layout) */
  center: [number, number];
  size: number;
  prominence: number;
  representative: ClusterRepresentative;
}

export type ClusterSpace = 'geo' | 'layout';

export interface ClustersResponse {
  city?: string;
  space?: ClusterSpace;
  clusters: PoiCluster[];
  previews: PoiCluster[];
  active: number;
}

// ---- Crowd scenes (GET /crowd/scenes, WS /crowd/stream) ----

export type Vec3 = [x: number, y: number, z: number];

/** A camera in scene metres (+Y up); fov: vertical, in degrees. */
export interface CrowdCamera {
  eye: Vec3;
  target: Vec3;
  fov: number;
}

export interface CrowdBounds {
  min: Vec3;
  max: Vec3;
}

/** nolod: every character at full resolution; vdr: view-dependent LOD; vdr+oc: LOD and occlusion culling. */
export type CrowdMode = 'nolod' | 'vdr' | 'vdr+oc';

export interface CrowdScene {
  id: string;
  title: string;
  description: string;
  characters: number;
  models: string[];
  /** Full-resolution triangles of all characters (null: not known before the scene is built). */
  triangles: number | null;
  /** How many static occluder boxes (walls, booths, rocks) the scene has. */
  occluders: number;
  /** The occluders of the default crowd as axis-aligned boxes (at most 256; absent from older servers). */
  occluder_boxes?: CrowdBounds[];
  bounds: CrowdBounds;
  default_camera: CrowdCamera;
  count: { default: number; min: number; max: number };
}

export interface CrowdRange {
  min: number;
  max: number;
}

export interface CrowdLimits {
  max_width: number;
  max_height: number;
  min_width: number;
  min_height: number;
  max_streams: number;
  /** More view messages per second close the stream (1008). */
  max_messages_per_s?: number;
  /** The server renders at most this many frames per second per stream. */
  max_fps?: number;
  poe: CrowdRange;
  quality: CrowdRange;
}

export interface CrowdAttribution {
  /** The model's name, or several names separated by commas ("Horse, Donkey, Cow"). */
  model: string;
  text: string;
  url?: string;
}

export interface CrowdScenesResponse {
  scenes: CrowdScene[];
  modes: CrowdMode[];
  limits: CrowdLimits;
  attribution: CrowdAttribution[];
}

/** Client -> server: the view to render; the latest one wins. */
export interface CrowdViewMessage {
  type: 'view';
  scene: string;
  mode: CrowdMode;
  poe: number;
  width: number;
  height: number;
  quality: number;
  camera: CrowdCamera;
  heatmap: boolean;
  animate: boolean;
  count?: number;
  /** Frames per second to hold while the camera moves or the crowd animates (0: always full quality). */
  target_fps?: number;
  /** The user is moving the camera (no full-quality frame until false). */
  interacting?: boolean;
}

export interface CrowdProgressMessage {
  type: 'progress';
  scene: string;
  stage: string;
  model?: string;
  done: number;
  total: number;
}

export interface CrowdReadyMessage {
  type: 'ready';
  scene: string;
  characters: number;
  triangles: number;
  default_camera: CrowdCamera;
  bounds: CrowdBounds;
}

export interface CrowdStatsMessage {
  type: 'stats';
  frame: number;
  scene: string;
  mode: CrowdMode;
  poe: number;
  width: number;
  height: number;
  characters: number;
  triangles: number;
  /** Full-resolution triangles of the crowd (not in the contract's first version). */
  full_triangles?: number;
  clusters: { drawn: number; frustum_culled: number; occluded: number };
  ms: { lod_cut: number; render: number; encode: number; frame: number; readback?: number };
  fps: number;
  bytes: number;
  /** How the frame was rendered: while moving (smaller, coarser) or at rest (full quality). */
  quality?: CrowdFrameQuality;
  /** View messages that changed the view before this frame was rendered. */
  view?: number;
  /** The picture came out the same as frame `frame`, which the client shows: no new frame was sent. */
  unchanged?: boolean;
}

export interface CrowdFrameQuality {
  mode: 'interactive' | 'still';
  level: number;
  /** Of the requested width and height. */
  scale: number;
  /** Pixels of error of the cut, in the requested frame's pixels. */
  poe: number;
  jpeg: number;
  target_fps: number;
}

export interface CrowdErrorMessage {
  type: 'error';
  error: { code: string; message: string; field?: string | null };
}

export type CrowdServerMessage = CrowdProgressMessage | CrowdReadyMessage | CrowdStatsMessage | CrowdErrorMessage;
