// Import limits (load/import_limits.hpp) and cooperative stopping in the loaders: every limit
// stops a load at the first excess with LimitExceeded naming the limit, fast and with bounded
// memory; an installed stop token stops a load with util::Stopped; nothing stays behind.

#include "load/csv.hpp"
#include "load/import_limits.hpp"
#include "load/load_error.hpp"
#include "load/metro_load.hpp"
#include "load/osm_input.hpp"
#include "load/osm_roads.hpp"
#include "load/poi_load.hpp"
#include "slowdown.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"
#include "util/stop.hpp"

#include <bzlib.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <thread>

namespace tourmap::load {
namespace {

using test::data_file;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::size_t open_fds() {
  return static_cast<std::size_t>(
      std::distance(std::filesystem::directory_iterator("/proc/self/fd"), std::filesystem::directory_iterator()));
}

// Spool files of the OSM loader still in the temp directory (there should never be any).
std::size_t spool_files() {
  std::size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::temp_directory_path()))
    n += e.path().filename().string().rfind("tourmap-osm-", 0) == 0 ? 1 : 0;
  return n;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

// Expects `f` to throw LimitExceeded for `limit`; returns its message.
template <class F>
std::string expect_limit(F&& f, const std::string& limit) {
  try {
    f();
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.limit(), limit) << e.what();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected LimitExceeded(" << limit << "), got: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected LimitExceeded(" << limit << "), nothing thrown";
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// --- the limits themselves ---

TEST(ImportLimits, ListedByNameAndSettable) {
  ImportLimits limits;
  auto all = list_limits(limits);
  std::set<std::string_view> names;
  for (const auto& l : all) {
    EXPECT_TRUE(names.insert(l.name).second) << l.name;
    EXPECT_GT(l.value, 0u) << l.name;
    EXPECT_TRUE(l.unit == "count" || l.unit == "bytes") << l.name;
  }
  EXPECT_EQ(all.size(), 28u);
  EXPECT_TRUE(names.count("max_pois"));
  EXPECT_TRUE(set_limit(limits, "max_pois", 7));
  EXPECT_EQ(limits.max_pois, 7u);
  EXPECT_FALSE(set_limit(limits, "max_nonsense", 7));
  // Headroom over the sample data: POIs per city on the order of 10^5.
  EXPECT_GE(ImportLimits{}.max_pois, 100'000u);
}

TEST(ImportLimits, LimitExceededCarriesNameValueAndPlace) {
  try {
    check_limit(6, 5, "max_pois", "p.csv line 7", "POIs");
    FAIL();
  } catch (const LoadError& e) {  // a LoadError, so every existing catch still handles it
    const auto* limit = dynamic_cast<const LimitExceeded*>(&e);
    ASSERT_NE(limit, nullptr);
    EXPECT_EQ(limit->limit(), "max_pois");
    EXPECT_EQ(limit->value(), 5u);
    EXPECT_EQ(e.where(), "p.csv line 7");
    EXPECT_STREQ(e.what(), "p.csv line 7: more than 5 POIs (limit max_pois = 5)");
  }
}

// --- CSV: bounded memory for any input ---

TEST(CsvLimits, SixtyMegabytesOfCommasFailFast) {
  const std::string commas(60 << 20, ',');
  const auto start = Clock::now();
  auto what = expect_limit([&] { parse_csv(commas, "commas.csv"); }, "max_csv_fields");
  EXPECT_LT(seconds_since(start), 1.0 * test::kSlowdown);  // stops at field 1,001 of the header
  EXPECT_TRUE(contains(what, "commas.csv line 1")) << what;
}

// The peak memory of the same parse, measured in a child process (ru_maxrss is per process):
// it was 2.7 GB (60 M empty strings); now the input and little else. Exits 0 when bounded.
[[noreturn]] void parse_commas_and_report_peak_memory() {
  auto rss_kb = [] {
    std::ifstream statm("/proc/self/statm");
    long size = 0;
    long resident = 0;
    statm >> size >> resident;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
  };
  const long before = rss_kb();
  std::string commas(60 << 20, ',');
  try {
    parse_csv(commas, "commas.csv");
  } catch (const LimitExceeded&) {
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const long grew = usage.ru_maxrss - before;
  std::fprintf(stderr, "peak RSS grew by %ld KiB\n", grew);
  std::_Exit(grew < 256 * 1024 ? 0 : 1);  // the 60 MiB input + headroom
}

TEST(CsvLimits, SixtyMegabytesOfCommasKeepPeakMemoryLow) {
  // A fresh process (re-executed, not forked from this one with its threads and heap).
  const auto style = GTEST_FLAG_GET(death_test_style);
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(parse_commas_and_report_peak_memory(), ::testing::ExitedWithCode(0), "peak RSS grew by");
  GTEST_FLAG_SET(death_test_style, style);
}

TEST(CsvLimits, FieldsPerRowAndBytesPerField) {
  ImportLimits limits;
  limits.max_csv_fields = 3;
  limits.max_csv_field_bytes = 8;
  EXPECT_EQ(parse_csv("a,b,c\n1,2,3\n", "ok.csv", limits).rows.size(), 1u);
  auto what = expect_limit([&] { parse_csv("a,b,c\n1,2,3,4\n", "wide.csv", limits); }, "max_csv_fields");
  EXPECT_TRUE(contains(what, "wide.csv line 2")) << what;
  what = expect_limit([&] { parse_csv("a,b,c\n1,\"123456789\",3\n", "long.csv", limits); }, "max_csv_field_bytes");
  EXPECT_TRUE(contains(what, "long.csv line 2")) << what;
  EXPECT_TRUE(contains(what, "field 2 ('b')")) << what;  // names the column
  // A header beyond the limit, and the default byte limit on one huge unquoted field.
  expect_limit([&] { parse_csv("a,b,c,d\n", "h.csv", limits); }, "max_csv_fields");
  expect_limit([&] { parse_csv("a\n" + std::string(2 << 20, 'x') + "\n", "x.csv"); }, "max_csv_field_bytes");
}

TEST(CsvLimits, StreamingReaderKeepsRfc4180Behaviour) {
  CsvReader reader("\xEF\xBB\xBFid,name\r\n1,\"Acton, \"\"Town\"\"\nnorth\"\r\n\r\n2,B\r\n", "s.csv");
  ASSERT_EQ(reader.header().size(), 2u);
  EXPECT_EQ(reader.header()[0], "id");
  ASSERT_TRUE(reader.next());
  EXPECT_EQ(reader.row()[1], "Acton, \"Town\"\nnorth");
  EXPECT_EQ(reader.line(), 2u);
  ASSERT_TRUE(reader.next());
  EXPECT_EQ(reader.row()[0], "2");
  EXPECT_EQ(reader.line(), 5u);
  EXPECT_FALSE(reader.next());
}

// --- metro: parallel duplicate edges are merged, counts are capped ---

std::string loom_with_duplicate_edges(std::size_t copies) {
  std::string json = R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"id":"a","station_id":"A","station_label":"Alpha"},"geometry":{"type":"Point","coordinates":[16.0,48.0]}},
    {"type":"Feature","properties":{"id":"b","station_id":"B","station_label":"Beta"},"geometry":{"type":"Point","coordinates":[16.1,48.1]}})";
  for (std::size_t i = 0; i < copies; ++i) {
    const char* line = i % 3 == 0 ? "U1" : i % 3 == 1 ? "U2" : "U3";
    // The first copy has a bend the others lack, to tell which geometry is kept.
    json += std::string(R"(,{"type":"Feature","properties":{"from":")") + (i % 2 ? "b" : "a") + R"(","to":")" +
            (i % 2 ? "a" : "b") + R"(","lines":[{"id":")" + line + R"(","label":")" + line +
            R"(","color":"ff0000"}]},"geometry":{"type":"LineString","coordinates":[[16.0,48.0],)" +
            (i == 0 ? "[16.05,48.02]," : "") + "[16.1,48.1]]}}";
  }
  return json + "]}";
}

TEST(MetroLimits, TwentyThousandDuplicateLoomEdgesBecomeOne) {
  const auto json = loom_with_duplicate_edges(20'000);
  const auto start = Clock::now();
  MetroLoadStats stats;
  auto net = parse_metro_loom(json, "dups.json", {}, &stats);
  EXPECT_LT(seconds_since(start), 5.0 * test::kSlowdown);
  ASSERT_EQ(net.edges.size(), 1u);
  EXPECT_EQ(net.edges[0].lines.size(), 3u);             // the union of the copies' lines
  EXPECT_EQ(net.edges[0].geometry.size(), 3u);          // the first copy's geometry
  EXPECT_EQ(net.lines.size(), 3u);
  EXPECT_EQ(stats.connections, 20'000u);
  EXPECT_EQ(stats.merged_connections, 19'999u);
}

TEST(MetroLimits, DuplicateConnectionRowsAreMergedToo) {
  std::string conns = "station1,station2,line\n";
  for (int i = 0; i < 20'000; ++i) conns += i % 2 ? "1,2,1\n" : "2,1,1\n";
  LondonCsvText files{"id,latitude,longitude,name\n1,51.5,-0.1,A\n2,51.6,-0.1,B\n", "line,name,colour\n1,L,ff0000\n",
                      conns, "s.csv", "l.csv", "c.csv"};
  MetroLoadStats stats;
  auto net = parse_metro_station_csvs(files, {}, &stats);
  ASSERT_EQ(net.edges.size(), 1u);
  EXPECT_EQ(net.edges[0].lines.size(), 1u);
  EXPECT_EQ(stats.merged_connections, 19'999u);
}

TEST(MetroLimits, NodesEdgesLinesConnectionsAndText) {
  ImportLimits limits;
  limits.max_metro_nodes = 1;
  auto what = expect_limit([&] { load_metro_loom(data_file("metro/loom_freiburg.json"), limits); }, "max_metro_nodes");
  EXPECT_TRUE(contains(what, "loom_freiburg.json feature")) << what;

  limits = {};
  limits.max_metro_edges = 10;
  expect_limit([&] { load_metro_loom(data_file("metro/loom_freiburg.json"), limits); }, "max_metro_edges");
  limits = {};
  limits.max_metro_lines = 2;
  expect_limit([&] { load_metro_loom(data_file("metro/loom_freiburg.json"), limits); }, "max_metro_lines");
  limits = {};
  limits.max_metro_geometry_points = 100;
  expect_limit([&] { load_metro_loom(data_file("metro/loom_freiburg.json"), limits); }, "max_metro_geometry_points");
  limits = {};
  limits.max_metro_connections = 100;
  expect_limit([&] { parse_metro_loom(loom_with_duplicate_edges(1'000), "d.json", limits); }, "max_metro_connections");
  limits = {};
  limits.max_json_values = 1'000;
  expect_limit([&] { load_metro_loom(data_file("metro/loom_freiburg.json"), limits); }, "max_json_values");

  // The CSV formats too.
  limits = {};
  limits.max_metro_nodes = 10;
  expect_limit([&] { load_metro_line_csv(data_file("metro/lisbon_metro_stations_metrodroid.csv"), limits); },
               "max_metro_nodes");
  expect_limit(
      [&] {
        load_metro_station_csvs(data_file("metro/london.stations.csv"), data_file("metro/london.lines.csv"),
                                data_file("metro/london.connections.csv"), limits);
      },
      "max_metro_nodes");
  limits = {};
  limits.max_metro_connections = 20;
  expect_limit([&] { load_metro_line_csv(data_file("metro/lisbon_metro_stations_metrodroid.csv"), limits); },
               "max_metro_connections");

  // A station name beyond max_name_bytes is refused, not truncated.
  const std::string long_name(2'000, 'x');
  what = expect_limit(
      [&] {
        parse_metro_loom(R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"id":"a",
          "station_id":"A","station_label":")" + long_name + R"("},"geometry":{"type":"Point","coordinates":[16,48]}}]})",
                         "n.json");
      },
      "max_name_bytes");
  EXPECT_TRUE(contains(what, "n.json feature 0")) << what;
  EXPECT_TRUE(contains(what, "station name")) << what;
}

// --- POIs ---

// (Built with append: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string.)
std::string poi_csv(std::size_t rows) {
  std::string csv = "name,lat,lon\n";
  for (std::size_t i = 0; i < rows; ++i) csv.append("P").append(std::to_string(i)).append(",48.2,16.3\n");
  return csv;
}

std::string poi_geojson(std::size_t features, const std::string& first_name = "") {
  std::string json = R"({"type":"FeatureCollection","features":[)";
  for (std::size_t i = 0; i < features; ++i) {
    if (i) json += ",";
    json += R"({"type":"Feature","properties":{"name":")";
    if (i == 0 && !first_name.empty())
      json += first_name;
    else
      json.append("P").append(std::to_string(i));
    json += R"("},"geometry":{"type":"Point","coordinates":[16.3,48.2]}})";
  }
  return json + "]}";
}

TEST(PoiLimits, CountCapStopsAtTheFirstPoiInExcess) {
  ImportLimits limits;
  limits.max_pois = 5;
  EXPECT_EQ(parse_pois_csv(poi_csv(5), "five.csv", {}, limits).size(), 5u);
  auto what = expect_limit([&] { parse_pois_csv(poi_csv(1'000), "many.csv", {}, limits); }, "max_pois");
  EXPECT_TRUE(contains(what, "many.csv line 7")) << what;  // header + 5 rows, then the 6th
  what = expect_limit([&] { parse_pois_geojson(poi_geojson(10), "many.geojson", {}, limits); }, "max_pois");
  EXPECT_TRUE(contains(what, "many.geojson feature 5")) << what;
  expect_limit([&] { load_pois(data_file("poi/berlin_museums_osm_r360.js"), {"museum"}, limits); }, "max_pois");
  // The defaults take the sample data.
  EXPECT_EQ(load_pois(data_file("poi/london_museums_wikipedia_glo.csv"), {"museum"}).size(), 232u);
}

TEST(PoiLimits, SixtyMegabyteNameIsRefusedNotTruncated) {
  // Not timed: most of the ~3 s here is building and JSON-parsing the 60 MB text (the name
  // check itself is one size comparison), so a clock bound only measured the machine's load.
  const std::string huge(60 << 20, 'n');
  auto what = expect_limit([&] { parse_pois_geojson(poi_geojson(3, huge), "huge.geojson"); }, "max_name_bytes");
  EXPECT_TRUE(contains(what, "huge.geojson feature 0")) << what.substr(0, 200);
  EXPECT_TRUE(contains(what, "name is 62914560 bytes long")) << what.substr(0, 200);
  EXPECT_LT(what.size(), 500u);  // the message does not quote the text
}

TEST(PoiLimits, TextFieldsOfCsvRecords) {
  const std::string long_name(1'025, 'n');
  auto what = expect_limit([&] { parse_pois_csv("id,name,lat,lon\n1,ok,48,16\n2," + long_name + ",48,16\n", "n.csv"); },
                           "max_name_bytes");
  EXPECT_TRUE(contains(what, "n.csv line 3: name is 1025 bytes long")) << what;
  what = expect_limit([&] { parse_pois_csv("name,lat,lon,category\nA,48,16," + long_name + "\n", "c.csv"); },
                      "max_name_bytes");
  EXPECT_TRUE(contains(what, "category")) << what;
  what = expect_limit(
      [&] { parse_pois_csv("name,lat,lon,url\nA,48,16,http://x/" + std::string(5'000, 'u') + "\n", "u.csv"); },
      "max_url_bytes");
  EXPECT_TRUE(contains(what, "URL")) << what;
  expect_limit([&] { parse_pois_csv("id,name,lat,lon\n" + std::string(300, 'i') + ",A,48,16\n", "i.csv"); },
               "max_id_bytes");
  // Exactly at the limit is fine.
  EXPECT_EQ(parse_pois_csv("name,lat,lon\n" + std::string(1'024, 'n') + ",48,16\n", "ok.csv")[0].name.size(), 1'024u);
}

// --- OSM roads: decompression bombs, entity caps ---

// gzip members of `bytes`, one compressed `copies` times in a row (a valid multi-member gzip
// file, as `cat a.gz b.gz` makes): 2 GiB of spaces take 2 MB and no time to build.
std::string gzip_member(const std::string& bytes) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&zs, static_cast<uLong>(bytes.size())), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  zs.avail_in = static_cast<uInt>(bytes.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

std::string bzip2_stream(const std::string& bytes) {
  std::string out(bytes.size() + bytes.size() / 100 + 600, '\0');  // the worst case, as bzlib documents it
  auto size = static_cast<unsigned>(out.size());
  EXPECT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &size, const_cast<char*>(bytes.data()),
                                     static_cast<unsigned>(bytes.size()), 9, 0, 0),
            BZ_OK);
  out.resize(size);
  return out;
}

const std::string kOsmHead = "<?xml version='1.0' encoding='UTF-8'?>\n<osm version=\"0.6\">\n";

// An OSM XML header followed by 2 GiB of whitespace: libosmium parses it without complaint (no
// entity, nothing to stop at) for as long as it lasts.
std::string gzip_bomb() {
  const auto spaces = gzip_member(std::string(8 << 20, ' '));
  std::string bomb = gzip_member(kOsmHead);
  for (int i = 0; i < 256; ++i) bomb += spaces;
  return bomb;
}

std::string bzip2_bomb() {
  const auto spaces = bzip2_stream(std::string(8 << 20, ' '));
  std::string bomb = bzip2_stream(kOsmHead);
  for (int i = 0; i < 256; ++i) bomb += spaces;
  return bomb;
}

TEST(OsmLimits, GzipBombIsRefusedByTheByteCapQuickly) {
  test::TempDir dir;
  const auto bomb = gzip_bomb();
  EXPECT_LT(bomb.size(), 4u << 20);
  const auto path = dir.write("bomb.osm.gz", bomb);
  const auto fds = open_fds();
  const auto spools = spool_files();
  // 256 MiB rather than the default 1 GiB: the inflated bytes are spooled to the temp dir, and
  // a test should not need a gigabyte of free disk.
  ImportLimits limits;
  limits.max_osm_decompressed_bytes = 256 << 20;
  const auto start = Clock::now();
  auto what = expect_limit([&] { load_osm_roads(path, nullptr, limits); }, "max_osm_decompressed_bytes");
  const double seconds = seconds_since(start);
  std::printf("gzip bomb (2 GiB of whitespace in %zu bytes) refused at 256 MiB after %.2f s\n", bomb.size(), seconds);
  EXPECT_LT(seconds, 10.0 * test::kSlowdown);  // ~0.5 s: 256 MiB inflated and spooled; libosmium never runs
  EXPECT_TRUE(contains(what, "bomb.osm.gz")) << what;
  EXPECT_EQ(open_fds(), fds);
  EXPECT_EQ(spool_files(), spools);

  ImportLimits small;
  small.max_osm_decompressed_bytes = 16 << 20;
  const auto small_start = Clock::now();
  try {
    load_osm_roads(path, nullptr, small);
    FAIL();
  } catch (const LimitExceeded& e) {
    EXPECT_EQ(e.value(), 16u << 20);
  }
  EXPECT_LT(seconds_since(small_start), 2.0 * test::kSlowdown);
}

TEST(OsmLimits, Bzip2BombIsRefusedByTheByteCap) {
  test::TempDir dir;
  const auto bomb = bzip2_bomb();
  EXPECT_LT(bomb.size(), 64u << 10);
  const auto path = dir.write("bomb.osm.bz2", bomb);
  const auto fds = open_fds();
  ImportLimits limits;
  limits.max_osm_decompressed_bytes = 64 << 20;
  const auto start = Clock::now();
  expect_limit([&] { load_osm_roads(path, nullptr, limits); }, "max_osm_decompressed_bytes");
  const double seconds = seconds_since(start);
  std::printf("bzip2 bomb (2 GiB of whitespace in %zu bytes) refused at 64 MiB after %.2f s\n", bomb.size(), seconds);
  EXPECT_LT(seconds, 5.0 * test::kSlowdown);
  EXPECT_EQ(open_fds(), fds);
}

TEST(OsmLimits, MultiMemberGzipAndConcatenatedBzip2LoadLikeOneStream) {
  test::TempDir dir;
  const auto xml = [] {
    std::string gz = read_bytes(data_file("roads/monaco.osm.gz"));
    // Decompress the sample with our own reader to get its XML.
    test::TempDir tmp;
    const auto path = tmp.write("m.osm.gz", gz);
    SpoolFile spool;
    const auto size = decompress_osm(path, OsmCompression::gzip, spool, 1ull << 30, "m.osm.gz");
    std::string text(size, '\0');
    EXPECT_EQ(::pread(spool.fd(), text.data(), size, 0), static_cast<ssize_t>(size));
    return text;
  }();
  const auto half = xml.size() / 2;
  const auto gz = dir.write("two.osm.gz", gzip_member(xml.substr(0, half)) + gzip_member(xml.substr(half)));
  const auto bz = dir.write("two.osm.bz2", bzip2_stream(xml.substr(0, half)) + bzip2_stream(xml.substr(half)));
  const auto plain = dir.write("one.osm", xml);
  OsmRoadStats a, b, c;
  const auto from_gz = load_osm_roads(gz, &a);
  const auto from_bz = load_osm_roads(bz, &b);
  const auto from_plain = load_osm_roads(plain, &c);
  EXPECT_GT(from_plain.edges.size(), 1000u);
  EXPECT_EQ(from_gz.edges.size(), from_plain.edges.size());
  EXPECT_EQ(from_bz.edges.size(), from_plain.edges.size());
  EXPECT_EQ(a.input_bytes, xml.size());
  EXPECT_EQ(b.input_bytes, xml.size());
  EXPECT_EQ(c.input_bytes, xml.size());
  // Truncated in the second member: an error, not half a network.
  const auto cut = dir.write("cut.osm.gz", gzip_member(xml.substr(0, half)) + gzip_member(xml.substr(half)).substr(0, 1000));
  try {
    load_osm_roads(cut);
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_TRUE(contains(e.what(), "cannot read OSM data")) << e.what();
  }
}

TEST(OsmLimits, EntityCapsStopTheParseAndLeaveNothingOpen) {
  const auto fds = open_fds();
  ImportLimits limits;
  limits.max_osm_nodes = 1'000;
  auto what = expect_limit([&] { load_osm_roads(data_file("roads/andorra.osm.gz"), nullptr, limits); }, "max_osm_nodes");
  EXPECT_TRUE(contains(what, "andorra.osm.gz after 1001 nodes")) << what;
  limits = {};
  limits.max_osm_ways = 10;
  expect_limit([&] { load_osm_roads(data_file("roads/West-Oakland.osm.bz2"), nullptr, limits); }, "max_osm_ways");
  limits = {};
  limits.max_road_nodes = 100;
  expect_limit([&] { load_osm_roads(data_file("roads/West-Oakland.osm.bz2"), nullptr, limits); }, "max_road_nodes");
  limits = {};
  limits.max_road_ways = 5;
  expect_limit([&] { load_osm_roads(data_file("roads/West-Oakland.osm.bz2"), nullptr, limits); }, "max_road_ways");
  limits = {};
  limits.max_road_edges = 100;
  expect_limit([&] { load_osm_roads(data_file("roads/West-Oakland.osm.bz2"), nullptr, limits); }, "max_road_edges");
  limits = {};
  limits.max_osm_nodes = 1'000;
  expect_limit([&] { load_osm_roads(data_file("roads/liechtenstein-latest.osm.pbf"), nullptr, limits); },
               "max_osm_nodes");
  EXPECT_EQ(open_fds(), fds);
}

TEST(OsmLimits, PbfBlobsAreCountedAndSizedBeforeDecoding) {
  const auto pbf = read_bytes(data_file("roads/liechtenstein-latest.osm.pbf"));
  const auto blobs = scan_pbf_blobs(pbf, 1'000'000, 1ull << 40);
  EXPECT_GT(blobs.count, 10u);
  EXPECT_GT(blobs.raw_bytes, pbf.size());  // raw sizes are decompressed sizes
  ImportLimits limits;
  limits.max_osm_pbf_blobs = 5;
  expect_limit([&] { load_osm_roads(data_file("roads/liechtenstein-latest.osm.pbf"), nullptr, limits); },
               "max_osm_pbf_blobs");
  limits = {};
  limits.max_osm_decompressed_bytes = blobs.raw_bytes - 1;
  expect_limit([&] { load_osm_roads(data_file("roads/liechtenstein-latest.osm.pbf"), nullptr, limits); },
               "max_osm_decompressed_bytes");
  limits.max_osm_decompressed_bytes = blobs.raw_bytes;
  OsmRoadStats stats;
  EXPECT_GT(load_osm_roads(data_file("roads/liechtenstein-latest.osm.pbf"), &stats, limits).edges.size(), 55'000u);
  EXPECT_EQ(stats.input_bytes, blobs.raw_bytes);
}

TEST(OsmLimits, PlainXmlSizeAndTagLengths) {
  test::TempDir dir;
  // (libosmium refuses values beyond 1,024 bytes itself: the default max_name_bytes.)
  const auto path = dir.write("r.osm", kOsmHead + R"(<node id="1" lat="0" lon="0"/><node id="2" lat="0" lon="0.001"/>
    <way id="10"><nd ref="1"/><nd ref="2"/><tag k="highway" v="residential"/><tag k="name" v=")" +
                                           std::string(500, 'n') + R"("/></way></osm>)");
  EXPECT_EQ(load_osm_roads(path).ways.at(0).name.size(), 500u);
  ImportLimits limits;
  limits.max_name_bytes = 100;
  auto what = expect_limit([&] { load_osm_roads(path, nullptr, limits); }, "max_name_bytes");
  EXPECT_TRUE(contains(what, "r.osm way 10: name tag is 500 bytes long")) << what;
  limits = {};
  limits.max_osm_decompressed_bytes = 100;
  expect_limit([&] { load_osm_roads(path, nullptr, limits); }, "max_osm_decompressed_bytes");
}

// --- stopping ---

class StopTest : public ::testing::Test {
 protected:
  StopTest() { token.deadline = Clock::now() - std::chrono::seconds(1); }  // already passed
  util::StopToken token;
};

TEST_F(StopTest, ExpiredDeadlineStopsEveryLoader) {
  const auto fds = open_fds();
  const auto spools = spool_files();
  util::StopScope scope(token);
  EXPECT_THROW(load_osm_roads(data_file("roads/monaco.osm.gz")), util::Stopped);  // not a LoadError
  EXPECT_THROW(load_osm_roads(data_file("roads/West-Oakland.osm.bz2")), util::Stopped);
  EXPECT_THROW(load_osm_roads(data_file("roads/liechtenstein-latest.osm.pbf")), util::Stopped);
  EXPECT_THROW(load_pois(data_file("poi/london_museums_wikipedia_glo.csv")), util::Stopped);
  EXPECT_THROW(load_pois(data_file("poi/vienna_sights_SEHENSWUERDIGOGD.json")), util::Stopped);
  EXPECT_THROW(load_metro_loom(data_file("metro/loom_wien.json")), util::Stopped);
  EXPECT_THROW(load_metro_line_csv(data_file("metro/lisbon_metro_stations_metrodroid.csv")), util::Stopped);
  EXPECT_EQ(open_fds(), fds);
  EXPECT_EQ(spool_files(), spools);
}

TEST_F(StopTest, ClientGoneStopsABombWhileItIsDecompressed) {
  test::TempDir dir;
  const auto path = dir.write("bomb.osm.gz", gzip_bomb());
  std::atomic<bool> gone{false};
  util::StopToken client;
  client.cancelled = &gone;
  util::StopScope scope(client);
  ImportLimits unlimited;
  unlimited.max_osm_decompressed_bytes = 1ull << 40;
  // The flag goes up while the loader is busy: it stops within a chunk.
  std::thread disconnect([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    gone = true;
  });
  const auto start = Clock::now();
  try {
    load_osm_roads(path, nullptr, unlimited);
    ADD_FAILURE() << "loaded";
  } catch (const util::Stopped& e) {
    EXPECT_EQ(e.reason, util::Stopped::Reason::client_gone);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected util::Stopped, got " << e.what();
  }
  disconnect.join();
  EXPECT_LT(seconds_since(start), 3.0 * test::kSlowdown);
}

}  // namespace
}  // namespace tourmap::load
