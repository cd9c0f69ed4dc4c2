// OSM imports (core/load/osm_roads: load_osm_roads, core/load/osm_context: load_osm_context,
// core/load/osm_pois: load_osm_pois, core/load/metro_osm: load_metro_osm, all through
// libosmium, as the importer calls them) on a file rewritten for every input. Built twice: fuzz_osm_xml writes roads.osm
// (XML), fuzz_osm_pbf writes roads.osm.pbf; libosmium picks the format from the extension.
// Clean error: load::LoadError (the loader wraps libosmium's exceptions). Either way no file
// descriptor may stay open (a server importing uploads would run out).

#include "fuzz_common.hpp"

#include "load/load_error.hpp"
#include "load/metro_osm.hpp"
#include "load/osm_context.hpp"
#include "load/osm_pois.hpp"
#include "load/osm_roads.hpp"

#include <cmath>

#ifndef TOURMAP_FUZZ_OSM_FILE
#error "define TOURMAP_FUZZ_OSM_FILE (roads.osm or roads.osm.pbf)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  const std::string path = fuzz::ScratchDir::get().write(TOURMAP_FUZZ_OSM_FILE, fuzz::as_view(data, size));
  const std::size_t fds = fuzz::open_fds();
  try {
    load::OsmRoadStats stats;
    const auto net = load::load_osm_roads(path, &stats);
    for (const auto& e : net.edges)
      FUZZ_CHECK(e.from < net.nodes.size() && e.to < net.nodes.size() && e.way < net.ways.size());
    for (const auto& w : net.ways) {
      FUZZ_CHECK(w.nodes.size() >= 2);
      for (auto n : w.nodes)
        FUZZ_CHECK(n < net.nodes.size());
    }
  } catch (const load::LoadError&) {
  }
  const auto located = [](const geo::LonLat& p) { return std::isfinite(p.lon) && std::isfinite(p.lat); };
  try {
    const auto context = load::load_osm_context(path);
    for (const auto& a : context.areas) {
      FUZZ_CHECK(!a.rings.empty());
      for (const auto& ring : a.rings) {
        FUZZ_CHECK(ring.size() >= 3);
        for (const auto& p : ring) FUZZ_CHECK(located(p));
      }
    }
    for (const auto& l : context.lines) {
      FUZZ_CHECK(l.points.size() >= 2);
      for (const auto& p : l.points) FUZZ_CHECK(located(p));
    }
    for (const auto& p : context.places) FUZZ_CHECK(!p.name.empty() && located(p.pos));
  } catch (const load::LoadError&) {
  }
  try {
    for (const auto& poi : load::load_osm_pois(path)) FUZZ_CHECK(!poi.name.empty() && located(poi.pos));
  } catch (const load::LoadError&) {
  }
  try {
    const auto metro = load::load_metro_osm(path, {"bus", "tram", "train", "subway"});
    for (const auto& e : metro.edges) FUZZ_CHECK(e.from < metro.nodes.size() && e.to < metro.nodes.size() && e.from != e.to);
    for (const auto& n : metro.nodes) FUZZ_CHECK(located(n.pos));
  } catch (const load::LoadError&) {
  }
  FUZZ_CHECK(fuzz::open_fds() <= fds);
  return 0;
}
