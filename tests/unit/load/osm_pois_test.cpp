// Points of interest from OSM (load/osm_pois.hpp): which tags make a place, its category,
// links and popularity, node and way of one place merged, the limits, and Liechtenstein's
// extract through load_pois.

#include "load/osm_pois.hpp"
#include "load/load_error.hpp"
#include "load/poi_load.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

namespace tourmap::load {
namespace {

std::string osm(const std::string& body) {
  return std::string(R"(<?xml version='1.0' encoding='UTF-8'?><osm version="0.6">)") + body + "</osm>";
}

std::string node(long id, double lon, double lat, const std::string& tags = "") {
  std::ostringstream out;
  out.precision(10);
  out << "<node id=\"" << id << "\" lat=\"" << lat << "\" lon=\"" << lon << "\"" << (tags.empty() ? "/>" : ">") << tags
      << (tags.empty() ? "" : "</node>");
  return out.str();
}

std::string way(long id, std::initializer_list<long> nodes, const std::string& tags) {
  std::string out = "<way id=\"" + std::to_string(id) + "\">";
  for (long n : nodes) out += "<nd ref=\"" + std::to_string(n) + "\"/>";
  return out + tags + "</way>";
}

std::string tag(const std::string& k, const std::string& v) { return "<tag k=\"" + k + "\" v=\"" + v + "\"/>"; }

const model::Poi* named(const std::vector<model::Poi>& pois, const std::string& name) {
  auto it = std::find_if(pois.begin(), pois.end(), [&](const model::Poi& p) { return p.name == name; });
  return it == pois.end() ? nullptr : &*it;
}

TEST(OsmPois, KeepsTouristPlacesWithANameAndTheirLinks) {
  test::TempDir dir;
  const auto path = dir.write(
      "t.osm",
      osm(node(1, 9.52, 47.14,
               tag("tourism", "museum") + tag("name", "Kunstmuseum") + tag("website", "https://kunstmuseum.li") +
                   tag("wikipedia", "de:Kunstmuseum Liechtenstein") + tag("wikidata", "Q1792") +
                   tag("wikimedia_commons", "File:Kunstmuseum Vaduz.jpg")) +
          node(2, 9.53, 47.15, tag("historic", "castle") + tag("name", "Burg") + tag("heritage", "2")) +
          node(3, 9.54, 47.16, tag("tourism", "hotel") + tag("name", "Hotel")) +         // not a sight
          node(4, 9.55, 47.17, tag("tourism", "viewpoint")) +                              // no name
          node(5, 9.56, 47.18, tag("historic", "yes") + tag("name", "Something")) +        // no kind
          node(6, 9.57, 47.19, tag("amenity", "place_of_worship") + tag("name", "Chapel")) +  // not notable
          node(7, 9.58, 47.20, tag("amenity", "place_of_worship") + tag("name", "Kathedrale") + tag("wikidata", "Q7")) +
          node(8, 9.59, 47.21, tag("tourism", "theme_park") + tag("name", "Park") + tag("url", "ftp://x"))));
  OsmPoiStats stats;
  const auto pois = load_osm_pois(path, &stats);
  ASSERT_EQ(pois.size(), 4u);
  const auto* museum = named(pois, "Kunstmuseum");
  ASSERT_TRUE(museum);
  EXPECT_EQ(museum->id, "n1");
  EXPECT_EQ(museum->category, "museum");
  EXPECT_NEAR(museum->pos.lon, 9.52, 1e-7);
  EXPECT_NEAR(museum->pos.lat, 47.14, 1e-7);
  EXPECT_EQ(museum->url, "https://kunstmuseum.li");
  EXPECT_EQ(museum->wikipedia, "https://de.wikipedia.org/wiki/Kunstmuseum_Liechtenstein");
  EXPECT_EQ(museum->image_url, "https://commons.wikimedia.org/wiki/Special:FilePath/Kunstmuseum_Vaduz.jpg");
  EXPECT_EQ(museum->popularity, 2 + 2 + 1);  // wikidata, wikipedia, a museum
  const auto* castle = named(pois, "Burg");
  ASSERT_TRUE(castle);
  EXPECT_EQ(castle->category, "castle");
  EXPECT_EQ(castle->popularity, 2 + 1);  // a national heritage listing, a castle
  const auto* cathedral = named(pois, "Kathedrale");
  ASSERT_TRUE(cathedral);
  EXPECT_EQ(cathedral->category, "place of worship");
  EXPECT_EQ(cathedral->wikipedia, "https://www.wikidata.org/wiki/Q7");  // no article: the item
  const auto* park = named(pois, "Park");
  ASSERT_TRUE(park);
  EXPECT_EQ(park->category, "theme park");
  EXPECT_EQ(park->url, "");  // not an http(s) link
  EXPECT_EQ(stats.unnamed, 1u);
  EXPECT_EQ(stats.from_nodes, 4u);
}

TEST(OsmPois, AWayIsPlacedAtItsNodesMeanAndMergedWithTheNodeOfThePlace) {
  test::TempDir dir;
  const auto path = dir.write(
      "w.osm",
      osm(node(1, 10.0, 50.0) + node(2, 10.002, 50.0) + node(3, 10.002, 50.002) + node(4, 10.0, 50.002) +
          node(5, 10.001, 50.001, tag("tourism", "museum") + tag("name", "Museum X")) +
          way(10, {1, 2, 3, 4, 1}, tag("building", "yes") + tag("tourism", "museum") + tag("name", "museum x") +
                                       tag("website", "https://x.example")) +
          // A second museum of another name: a place of its own, at the mean of its corners.
          node(6, 10.1, 50.1) + node(7, 10.104, 50.1) + node(8, 10.104, 50.104) +
          way(11, {6, 7, 8, 6}, tag("tourism", "gallery") + tag("name", "Galerie"))));
  OsmPoiStats stats;
  const auto pois = load_osm_pois(path, &stats);
  ASSERT_EQ(pois.size(), 2u);
  const auto* museum = named(pois, "Museum X");
  ASSERT_TRUE(museum);
  EXPECT_EQ(museum->id, "n5");                        // the node's position and id
  EXPECT_EQ(museum->url, "https://x.example");        // the way's link
  const auto* gallery = named(pois, "Galerie");
  ASSERT_TRUE(gallery);
  EXPECT_EQ(gallery->id, "w11");
  EXPECT_NEAR(gallery->pos.lon, (10.1 + 10.104 + 10.104) / 3, 1e-7);  // the closing node once
  EXPECT_NEAR(gallery->pos.lat, (50.1 + 50.1 + 50.104) / 3, 1e-7);
  EXPECT_EQ(stats.merged, 1u);
  EXPECT_EQ(stats.from_ways, 1u);
}

TEST(OsmPois, LimitsStopTheLoadNamingTheEntity) {
  test::TempDir dir;
  const auto path = dir.write("l.osm", osm(node(1, 9.5, 47.1, tag("tourism", "museum") + tag("name", "A")) +
                                          node(2, 9.6, 47.2, tag("tourism", "museum") + tag("name", "B"))));
  ImportLimits limits;
  limits.max_pois = 1;
  try {
    load_osm_pois(path, nullptr, limits);
    FAIL() << "no limit";
  } catch (const LimitExceeded& e) {
    EXPECT_NE(std::string(e.what()).find("max_pois"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("node 2"), std::string::npos) << e.what();
  }
  limits = {};
  limits.max_name_bytes = 0;
  EXPECT_THROW(load_osm_pois(path, nullptr, limits), LimitExceeded);
  EXPECT_THROW(load_osm_pois(dir.write("bad.osm", "<osm><node id="), nullptr), LoadError);
}

TEST(OsmPois, LiechtensteinExtractThroughLoadPois) {
  // The shared extract (2015) through load_pois, as a manifest uses it: its named museums,
  // castles, ruins, viewpoints, memorials, theatres and attractions (hotels, information
  // boards and picnic sites are not sights); the two ways of one ruin are one place.
  const auto pois = load_pois(test::data_file("roads/liechtenstein-latest.osm.pbf"));
  EXPECT_EQ(pois.size(), 26u);
  std::set<std::string> ids, categories;
  for (const auto& p : pois) {
    EXPECT_FALSE(p.name.empty());
    EXPECT_GT(p.pos.lon, 9.4);
    EXPECT_LT(p.pos.lon, 9.7);
    EXPECT_GT(p.pos.lat, 47.0);
    EXPECT_LT(p.pos.lat, 47.3);
    EXPECT_TRUE(ids.insert(p.id).second) << p.id;
    categories.insert(p.category);
  }
  EXPECT_TRUE(categories.count("museum")) << "no museum";
  EXPECT_TRUE(categories.count("castle")) << "no castle";
  EXPECT_TRUE(categories.count("viewpoint")) << "no viewpoint";
  const auto* museum = named(pois, "Kunstmuseum Liechtenstein");  // a building: a way
  ASSERT_TRUE(museum);
  EXPECT_EQ(museum->id, "w28712148");
  EXPECT_EQ(museum->category, "museum");
  EXPECT_EQ(std::count_if(pois.begin(), pois.end(), [](const model::Poi& p) { return p.name == "Burgruinie Unterer Schellenberg"; }), 1);
}

}  // namespace
}  // namespace tourmap::load
