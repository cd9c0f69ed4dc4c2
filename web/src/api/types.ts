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
}

export interface CityDetail extends CitySummary {
  lines: MetroLine[];
  poi_categories: string[];
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

/** Messages of the /api/v1/events WebSocket. */
export type ServerEvent =
  | { type: 'hello'; catalog_version: number; last_import?: LastImport }
  | { type: 'catalog'; catalog_version: number; last_import?: LastImport }
  | { type: 'pong' }
  | { type: 'error'; code: string; message: string };

/** GET /api/v1/roads/{id}?format=topology: nodes once each, ways as lists of node indices. */
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
}

export type DeformBody = DeformCommon &
  (
    | { regions: FocusRegion[] }
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
  positions?: number[];
  grid: DeformGrid | null;
  guides?: { vertex: number; from: LonLat; target: LonLat; to: LonLat }[];
  stats: DeformStats;
  attribution: string[];
}
