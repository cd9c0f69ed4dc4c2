-- tourmap store, version 1: cities with metro networks and POIs, road networks, the import
-- log and a cache of computed results. Coordinates are WGS84 lon/lat degrees.

-- Every import gets a row; its id is the version stamped on what it wrote, so readers can tell
-- when a city or road network changed without comparing contents.
CREATE TABLE imports (
  id          INTEGER PRIMARY KEY AUTOINCREMENT,
  kind        TEXT NOT NULL CHECK (kind IN ('metro', 'pois', 'roads')),
  target_id   TEXT NOT NULL,           -- city id or road network id
  source      TEXT NOT NULL,           -- file name(s)
  fingerprint TEXT NOT NULL,           -- hash of the source bytes: re-importing the same file is a no-op
  rows        INTEGER NOT NULL,
  seconds     REAL NOT NULL,
  imported_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
CREATE INDEX imports_target ON imports (kind, target_id);

CREATE TABLE cities (
  id          TEXT PRIMARY KEY,
  name        TEXT NOT NULL,
  min_lon     REAL NOT NULL, min_lat REAL NOT NULL, max_lon REAL NOT NULL, max_lat REAL NOT NULL,
  proj_lon0   REAL NOT NULL,           -- local transverse Mercator projection origin
  proj_lat0   REAL NOT NULL,
  projection  TEXT NOT NULL,           -- human-readable description of the projection
  attribution TEXT NOT NULL DEFAULT '',     -- of the metro data
  poi_attribution TEXT NOT NULL DEFAULT '', -- of the POI data
  version     INTEGER NOT NULL         -- imports.id of the last import touching the city
);

CREATE TABLE metro_lines (
  city_id TEXT NOT NULL REFERENCES cities (id) ON DELETE CASCADE,
  idx     INTEGER NOT NULL,            -- position in the network's line list
  id      TEXT NOT NULL,
  label   TEXT NOT NULL,
  color   TEXT NOT NULL DEFAULT '',
  PRIMARY KEY (city_id, idx),
  UNIQUE (city_id, id)
);

-- Nodes of the line graph: stations, and track junctions that are not stations.
CREATE TABLE metro_nodes (
  city_id    TEXT NOT NULL REFERENCES cities (id) ON DELETE CASCADE,
  idx        INTEGER NOT NULL,
  id         TEXT NOT NULL,
  station_id TEXT,                     -- NULL for a junction
  name       TEXT NOT NULL DEFAULT '',
  lon        REAL NOT NULL,
  lat        REAL NOT NULL,
  PRIMARY KEY (city_id, idx),
  UNIQUE (city_id, id)
);

CREATE TABLE metro_edges (
  city_id   TEXT NOT NULL REFERENCES cities (id) ON DELETE CASCADE,
  idx       INTEGER NOT NULL,
  from_idx  INTEGER NOT NULL,
  to_idx    INTEGER NOT NULL,
  line_idxs TEXT NOT NULL,             -- JSON array of metro_lines.idx
  geometry  BLOB NOT NULL,             -- packed little-endian float64 lon,lat pairs
  PRIMARY KEY (city_id, idx)
);

CREATE TABLE pois (
  city_id    TEXT NOT NULL REFERENCES cities (id) ON DELETE CASCADE,
  idx        INTEGER NOT NULL,
  id         TEXT NOT NULL,
  name       TEXT NOT NULL,
  lon        REAL NOT NULL,
  lat        REAL NOT NULL,
  category   TEXT NOT NULL DEFAULT '',
  image_url  TEXT NOT NULL DEFAULT '',
  url        TEXT NOT NULL DEFAULT '',
  wikipedia  TEXT NOT NULL DEFAULT '',
  rank       REAL,
  popularity REAL,
  PRIMARY KEY (city_id, idx),
  UNIQUE (city_id, id)
);

CREATE TABLE road_networks (
  id          TEXT PRIMARY KEY,
  name        TEXT NOT NULL,
  min_lon     REAL NOT NULL, min_lat REAL NOT NULL, max_lon REAL NOT NULL, max_lat REAL NOT NULL,
  proj_lon0   REAL NOT NULL,
  proj_lat0   REAL NOT NULL,
  projection  TEXT NOT NULL,
  attribution TEXT NOT NULL DEFAULT '',
  node_count  INTEGER NOT NULL,
  way_count   INTEGER NOT NULL,
  edge_count  INTEGER NOT NULL,
  version     INTEGER NOT NULL
);

CREATE TABLE road_nodes (
  network_id TEXT NOT NULL REFERENCES road_networks (id) ON DELETE CASCADE,
  idx        INTEGER NOT NULL,
  osm_id     INTEGER NOT NULL,
  lon        REAL NOT NULL,
  lat        REAL NOT NULL,
  PRIMARY KEY (network_id, idx)
) WITHOUT ROWID;

CREATE TABLE road_ways (
  network_id TEXT NOT NULL REFERENCES road_networks (id) ON DELETE CASCADE,
  idx        INTEGER NOT NULL,
  osm_id     INTEGER NOT NULL,
  highway    TEXT NOT NULL,            -- road class (OSM highway=*)
  name       TEXT NOT NULL DEFAULT '',
  PRIMARY KEY (network_id, idx)
) WITHOUT ROWID;

-- Graph edges: consecutive node pairs of each way, in way order.
CREATE TABLE road_edges (
  network_id TEXT NOT NULL REFERENCES road_networks (id) ON DELETE CASCADE,
  idx        INTEGER NOT NULL,
  way_idx    INTEGER NOT NULL,
  from_idx   INTEGER NOT NULL,
  to_idx     INTEGER NOT NULL,
  PRIMARY KEY (network_id, idx)
) WITHOUT ROWID;

-- Computed results (layouts, deformations, cluster trees), keyed by a hash of
-- (kind, input versions, parameters).
CREATE TABLE result_cache (
  key         TEXT PRIMARY KEY,
  kind        TEXT NOT NULL,
  created_at  TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  last_used   TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  hits        INTEGER NOT NULL DEFAULT 0,
  content_type TEXT NOT NULL,
  body        BLOB NOT NULL
);
CREATE INDEX result_cache_kind ON result_cache (kind, last_used);
