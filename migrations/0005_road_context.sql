-- tourmap store, version 5: the context layers of a road network (issue 15), imported from the
-- same OSM extract in the same transaction as its roads (core/load/osm_context.hpp): areas
-- (sea, water, parks, woods, land use, buildings), lines (rivers, streams, canals, railways)
-- and places (names with a label rank). One row per feature, in the order the loader gave.
-- geometry: little-endian; an area is uint32 ring count, then per ring uint32 point count and
-- that many (float64 lon, float64 lat); a line is one such ring; a place one (lon, lat) pair.
-- Road networks imported before this version have a different fingerprint
-- (store/importer.hpp: kRoadProcessing), so the next import of the same file fills this in.
CREATE TABLE road_context (
  network_id TEXT NOT NULL REFERENCES road_networks (id) ON DELETE CASCADE,
  seq        INTEGER NOT NULL,
  layer      TEXT NOT NULL CHECK (layer IN ('area', 'line', 'place')),
  kind       TEXT NOT NULL,             -- model/context.hpp's kind names
  name       TEXT NOT NULL DEFAULT '',
  rank       INTEGER NOT NULL DEFAULT 0,  -- places: label priority, lower first
  tunnel     INTEGER NOT NULL DEFAULT 0,  -- lines: 1 in a tunnel or culvert
  geometry   BLOB NOT NULL,
  PRIMARY KEY (network_id, seq)
) WITHOUT ROWID;
