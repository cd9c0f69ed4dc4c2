// The map export (GET /api/v1/cities/{id}/map.svg|pdf|png) against a real server: formats,
// sizes, the shared layout cache, revalidation and bad input.

#include "live_server_suite.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <regex>
#include <set>
#include <string>

namespace tourmap::test {
namespace {

class MapExport : public LiveServerSuite<MapExport> {};

std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& png) {
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(png.at(at + i));
    return v;
  };
  return {be32(16), be32(20)};
}

TEST_F(MapExport, SvgShowsTheLayoutsStationNamesAsText) {
  // The layout first: the export of the same parameters reuses it.
  const auto layout = live->get_json("/api/v1/cities/vienna/layout?lengths=uniform&solver=fast");
  std::set<std::string> names;
  for (const auto& f : layout["stations"]["features"]) names.insert(f["properties"]["name"].get<std::string>());
  auto r = live->get("/api/v1/cities/vienna/map.svg?lengths=uniform&solver=fast");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.header("content-type"), "image/svg+xml");
  EXPECT_EQ(r.header("content-disposition"), "inline; filename=\"vienna-metro-a3.svg\"");
  EXPECT_EQ(r.header("x-result-cache"), "hit");
  EXPECT_NE(r.header("content-security-policy").find("default-src 'none'"), std::string::npos);
  EXPECT_NE(r.body.find("width=\"420mm\" height=\"297mm\""), std::string::npos);
  EXPECT_NE(r.body.find(">Vienna</tspan></text>"), std::string::npos);  // the title
  // Every station label is text, and the name of one of the layout's stations.
  const std::regex label("<text class=\"station-label\"[^>]*>(.*?)</text>");
  const std::regex tspan("<tspan[^>]*>([^<]*)</tspan>");
  std::size_t labels = 0;
  for (auto it = std::sregex_iterator(r.body.begin(), r.body.end(), label); it != std::sregex_iterator(); ++it) {
    std::string text, inner = (*it)[1];
    for (auto t = std::sregex_iterator(inner.begin(), inner.end(), tspan); t != std::sregex_iterator(); ++t) {
      if (!text.empty()) text += ' ';
      text += std::regex_replace((*t)[1].str(), std::regex("&amp;"), "&");
    }
    EXPECT_TRUE(names.count(text)) << text;
    ++labels;
  }
  EXPECT_GT(labels, names.size() / 2) << "most stations are named on A3";
  EXPECT_NE(r.body.find("Wiener Linien"), std::string::npos);  // attribution
}

TEST_F(MapExport, PngHasTheRequestedSize) {
  auto r = live->get("/api/v1/cities/vienna/map.png?width=800&height=600");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.header("content-type"), "image/png");
  EXPECT_EQ(r.header("content-disposition"), "inline; filename=\"vienna-metro.png\"");
  EXPECT_EQ(r.body.substr(1, 3), "PNG");
  EXPECT_EQ(png_size(r.body), (std::pair<std::uint32_t, std::uint32_t>{800, 600}));
  // A3 at 300 dpi, the print size the limits must allow.
  r = live->get("/api/v1/cities/vienna/map.png?paper=a3&dpi=300");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(png_size(r.body), (std::pair<std::uint32_t, std::uint32_t>{4961, 3508}));
  r = live->get("/api/v1/cities/lisbon/map.png?paper=a4&orientation=portrait&dpi=150");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(png_size(r.body), (std::pair<std::uint32_t, std::uint32_t>{1240, 1754}));
}

TEST_F(MapExport, PdfOnPaper) {
  auto r = live->get("/api/v1/cities/lisbon/map.pdf?paper=a4");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.header("content-type"), "application/pdf");
  EXPECT_EQ(r.header("content-disposition"), "inline; filename=\"lisbon-metro-a4.pdf\"");
  EXPECT_EQ(r.body.rfind("%PDF-", 0), 0u);
  EXPECT_NE(r.body.find("/MediaBox [ 0 0 841.889764 595.275591 ]"), std::string::npos);
  EXPECT_TRUE(std::regex_search(r.body, std::regex("DejaVuSansCondensed-Bold")));
  r = live->get("/api/v1/cities/lisbon/map.pdf?width=600&height=400");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.body.find("/MediaBox [ 0 0 600 400 ]"), std::string::npos);
}

TEST_F(MapExport, RevalidatesWithItsEtag) {
  const std::string path = "/api/v1/cities/lisbon/map.svg?width=900&height=700";
  auto first = live->get(path);
  ASSERT_EQ(first.status, 200);
  const auto etag = first.header("etag");
  ASSERT_FALSE(etag.empty());
  EXPECT_EQ(live->get(path, {{"If-None-Match", etag}}).status, 304);
  EXPECT_EQ(live->get("/api/v1/cities/lisbon/map.svg?width=901&height=700", {{"If-None-Match", etag}}).status, 200);
  auto pdf = live->get("/api/v1/cities/lisbon/map.pdf");
  ASSERT_EQ(pdf.status, 200);
  EXPECT_EQ(live->get("/api/v1/cities/lisbon/map.pdf", {{"If-None-Match", pdf.header("etag")}}).status, 304);
}

TEST_F(MapExport, BadInputNamesTheField) {
  expect_error(live->get("/api/v1/cities/atlantis/map.svg"), 404, "id");
  expect_error(live->get("/api/v1/cities/vienna/map.svg?width=50&height=600"), 400, "width");
  expect_error(live->get("/api/v1/cities/vienna/map.svg?width=800"), 400, "height");
  expect_error(live->get("/api/v1/cities/vienna/map.svg?width=800&height=1e9"), 400, "height");
  expect_error(live->get("/api/v1/cities/vienna/map.svg?width=800&height=-600"), 400, "height");
  expect_error(live->get("/api/v1/cities/vienna/map.svg?paper=a0"), 400, "paper");
  expect_error(live->get("/api/v1/cities/vienna/map.svg?paper=a4&height=600"), 400, "height");
  expect_error(live->get("/api/v1/cities/vienna/map.svg?dpi=300"), 400, "dpi");
  expect_error(live->get("/api/v1/cities/vienna/map.png?dpi=0"), 400, "dpi");
  expect_error(live->get("/api/v1/cities/vienna/map.png?width=10000&height=9000"), 413, "width");
  expect_error(live->get("/api/v1/cities/vienna/map.png?paper=a3&dpi=600"), 413, "dpi");
  expect_error(live->get("/api/v1/cities/vienna/map.pdf?width=800&height=15000"), 400, "height");
  expect_error(live->get("/api/v1/cities/vienna/map.pdf?solver=gurobi"), 400, "solver");
  EXPECT_EQ(live->get("/api/v1/cities/vienna/map.gif").status, 404);
}

}  // namespace
}  // namespace tourmap::test
