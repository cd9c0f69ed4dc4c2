#include "server/static_files.hpp"
#include "temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace tourmap::server {
namespace {

class StaticFilesTest : public ::testing::Test {
 protected:
  StaticFilesTest() {
    dir.write("web/index.html", "<html>app</html>");
    dir.write("web/assets/app-1234.js", "console.log(1)");
    dir.write("secret.txt", "do not serve");
    std::filesystem::create_symlink(dir.path() / "secret.txt", dir.path() / "web" / "link.txt");
  }
  test::TempDir dir;
};

TEST_F(StaticFilesTest, ServesIndexAndAssetsWithHeaders) {
  StaticFiles files(dir.file("web"));
  auto index = files.serve("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->body, "<html>app</html>");
  EXPECT_EQ(index->content_type, "text/html; charset=utf-8");
  auto js = files.serve("/assets/app-1234.js");
  ASSERT_TRUE(js);
  EXPECT_EQ(js->content_type, "text/javascript; charset=utf-8");
  bool immutable = false;
  for (const auto& [k, v] : js->headers) immutable |= k == "Cache-Control" && v.find("immutable") != std::string::npos;
  EXPECT_TRUE(immutable);
}

TEST_F(StaticFilesTest, RefusesTraversalAndSymlinksOut) {
  StaticFiles files(dir.file("web"));
  EXPECT_FALSE(files.serve("/../secret.txt"));
  EXPECT_FALSE(files.serve("/assets/../../secret.txt"));
  EXPECT_FALSE(files.serve("/..\\secret.txt"));
  EXPECT_FALSE(files.serve("/link.txt"));
  EXPECT_FALSE(files.serve("/missing.js"));
  EXPECT_FALSE(files.serve(""));
}

TEST(Mime, KnownTypes) {
  EXPECT_EQ(mime_type(".svg"), "image/svg+xml");
  EXPECT_EQ(mime_type(".geojson"), "application/geo+json");
  EXPECT_EQ(mime_type(".unknown"), "application/octet-stream");
}

}  // namespace
}  // namespace tourmap::server
