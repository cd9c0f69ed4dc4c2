#include "load/load_error.hpp"
#include "load/poi_load.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

namespace tourmap::load {
namespace {

using test::data_file;

TEST(PoiLoad, ViennaGeoJsonWithImages) {
  auto pois = load_pois(data_file("poi/vienna_sights_SEHENSWUERDIGOGD.json"), {"sight"});
  ASSERT_EQ(pois.size(), 63u);
  EXPECT_EQ(pois[0].name, "Sigmund Freud Museum");
  EXPECT_EQ(pois[0].id, "SEHENSWUERDIGOGD.488262");
  EXPECT_EQ(pois[0].image_url, "https://www.wien.gv.at/viennagis/bubble/freudmuseum.jpg");
  EXPECT_EQ(pois[0].url, "http://www.freud-museum.at");
  EXPECT_EQ(pois[0].category, "sight");
  for (const auto& p : pois) EXPECT_FALSE(p.image_url.empty()) << p.name;
}

TEST(PoiLoad, LondonCsvRepairsMojibakeAndKeepsWikipedia) {
  auto pois = load_pois(data_file("poi/london_museums_wikipedia_glo.csv"), {"museum"});
  ASSERT_EQ(pois.size(), 232u);
  std::size_t with_wikipedia = 0;
  bool globe = false;
  for (const auto& p : pois) {
    with_wikipedia += p.wikipedia.empty() ? 0 : 1;
    if (p.name == "Shakespeare\xE2\x80\x99s Globe Theatre") globe = true;
    EXPECT_EQ(p.name.find("\xC3\xA2\xE2\x82\xAC"), std::string::npos) << p.name;
    EXPECT_FALSE(p.category.empty());
  }
  EXPECT_EQ(with_wikipedia, 214u);
  EXPECT_TRUE(globe);
}

TEST(PoiLoad, BerlinJsArray) {
  auto pois = load_pois(data_file("poi/berlin_museums_osm_r360.js"), {"museum"});
  ASSERT_EQ(pois.size(), 92u);
  EXPECT_EQ(pois[0].name, "Altes Museum");
  EXPECT_EQ(pois[0].id, "15968753");
  EXPECT_NEAR(pois[0].pos.lon, 13.3988098410779, 1e-12);
}

TEST(PoiLoad, RankAndPopularityWhenPresent) {
  auto pois = parse_pois_csv("name,lat,lon,rank,popularity\nA,1,2,3,0.5\nB,1,2,NULL,\n", "r.csv");
  ASSERT_EQ(pois.size(), 2u);
  EXPECT_EQ(pois[0].rank, 3.0);
  EXPECT_EQ(pois[0].popularity, 0.5);
  EXPECT_FALSE(pois[1].rank.has_value());
  EXPECT_EQ(pois[0].id, "L2");  // no id column: the line number
}

TEST(PoiLoad, ErrorsNameTheRecord) {
  try {
    parse_pois_geojson(R"({"type":"FeatureCollection","features":[
      {"type":"Feature","properties":{"name":"ok"},"geometry":{"type":"Point","coordinates":[1,2]}},
      {"type":"Feature","properties":{"name":"bad"},"geometry":{"type":"Point","coordinates":[1,95]}}]})",
                       "p.geojson");
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where(), "p.geojson feature 1");
  }
  EXPECT_THROW(parse_pois_csv("name,lat\nA,1\n", "m.csv"), LoadError);                  // no lon column
  EXPECT_THROW(parse_pois_csv("name,lat,lon\n,1,2\n", "n.csv"), LoadError);             // no name
  EXPECT_THROW(parse_pois_js_array("var x = 5;", "x.js"), LoadError);                    // no array
  EXPECT_THROW(parse_pois_js_array("[{\"name\":\"a\"}]", "y.js"), LoadError);            // no position
  EXPECT_THROW(parse_pois_csv("id,name,lat,lon\n1,a,1,2\n1,b,1,2\n", "dup.csv"), LoadError);  // duplicate id
}

}  // namespace
}  // namespace tourmap::load
