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
