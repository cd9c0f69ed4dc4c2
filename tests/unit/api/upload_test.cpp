// Uploaded import bodies: format sniffing and the temporary directory's lifetime.

#include "api/upload.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace tourmap::api {
namespace {

TEST(Upload, SniffsOsmFormats) {
  EXPECT_EQ(sniff_osm_extension(std::string("\x1f\x8b\x08\x00", 4)), "osm.gz");
  EXPECT_EQ(sniff_osm_extension("BZh91AY&SY"), "osm.bz2");
  EXPECT_EQ(sniff_osm_extension(std::string("\x00\x00\x00\x0d\x0a\x09OSMHeader\x18\x7c", 17)), "osm.pbf");
  EXPECT_EQ(sniff_osm_extension("<?xml version='1.0'?><osm version='0.6'/>"), "osm");
  EXPECT_EQ(sniff_osm_extension("\n  <osm version='0.6'/>"), "osm");
  EXPECT_EQ(sniff_osm_extension("name,lon,lat\n"), "");
  EXPECT_EQ(sniff_osm_extension(""), "");
}

TEST(Upload, SniffsPoiFormats) {
  EXPECT_EQ(sniff_poi_extension(R"({"type":"FeatureCollection","features":[]})"), "json");
  EXPECT_EQ(sniff_poi_extension("\xEF\xBB\xBF  {}"), "json");
  EXPECT_EQ(sniff_poi_extension(R"([{"name":"a"}])"), "js");
  EXPECT_EQ(sniff_poi_extension("var museums = [];"), "js");
  EXPECT_EQ(sniff_poi_extension("name,lon,lat\nA,1,2\n"), "csv");
}

TEST(Upload, DirectoryHoldsFilesUntilDestroyed) {
  std::filesystem::path dir;
  {
    UploadDir upload;
    auto path = upload.write("monaco.osm", "<osm/>");
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(text, "<osm/>");
    dir = std::filesystem::path(path).parent_path();
    EXPECT_TRUE(std::filesystem::is_directory(dir));
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// A server killed during an upload leaves its directory; the next start removes it, but never
// one of a process that still runs (servers may share a temp dir).
TEST(Upload, StaleDirectoriesOfDeadProcessesAreRemoved) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::temp_directory_path() / ("tourmap-upload-test-" + std::to_string(::getpid()));
  fs::create_directories(parent);
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const auto stale = parent / ("tourmap-upload-" + std::to_string(dead) + "-AbCdEf");
  fs::create_directories(stale);
  std::ofstream(stale / "roads.osm") << "<osm/>";
  const auto unrelated = parent / "tourmap-upload-notapid";
  fs::create_directories(unrelated);
  {
    UploadDir live(parent);  // this process's: kept
    const auto mine = fs::path(live.write("a.osm", "<osm/>")).parent_path();
    EXPECT_EQ(mine.filename().string().rfind("tourmap-upload-" + std::to_string(::getpid()) + "-", 0), 0u);
    EXPECT_EQ(remove_stale_uploads(parent), 1u);
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(mine));
    EXPECT_TRUE(fs::exists(unrelated));
  }
  fs::remove_all(parent);
}

}  // namespace
}  // namespace tourmap::api
