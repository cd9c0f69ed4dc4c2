// The deformation service's caches are bounded in bytes: a prepared system (grid, matrices,
// Cholesky factor) of a fine grid holds tens of MB, and they used to be kept 16 at a time
// whatever their size (20 large-grid deformations took the server from 1.7 to 3.0 GB).

#include "api/deform_service.hpp"
#include "store/importer.hpp"
#include "store/migrate.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

namespace tourmap::api {
namespace {

Request focus_request(int n) {
  Request req;
  req.method = "POST";
  req.path = "/api/v1/deform/focus";
  req.content_type = "application/json";
  req.body = R"({"roads":"monaco","grid":{"kind":"uniform","n":)" + std::to_string(n) +
             R"(},"solver":"cholesky","regions":[{"center":[7.42,43.735],"radius_m":300,"scale":2}],)"
             R"("output":{"roads":"none"}})";
  return req;
}

TEST(DeformService, PreparedSystemsStayWithinTheirByteBudget) {
  test::TempDir dir;
  store::DbPool pool(dir.file("t.db"));
  {
    auto db = pool.acquire();
    store::migrate(*db);
    store::import_roads(*db, {{"monaco", "Monaco", "OSM"}, test::data_file("roads/monaco.osm.gz"), false});
  }
  Catalog catalog(pool);
  DeformLimits limits;
  limits.prepared_cache_bytes = 24u << 20;
  DeformService deform(catalog, limits);
  std::size_t largest = 0;
  for (int n = 60; n <= 120; n += 10) {
    const auto r = deform.handle(DeformApp::focus, focus_request(n));
    ASSERT_EQ(r.status, 200) << r.body;
    const auto stats = deform.cache_stats();
    EXPECT_LE(stats.prepared_bytes, limits.prepared_cache_bytes) << "after grid n=" << n;
    largest = std::max(largest, stats.prepared_bytes);
  }
  // The budget was reached (so eviction, not a lack of work, kept it) and entries went.
  EXPECT_GT(largest, limits.prepared_cache_bytes / 2);
  EXPECT_LT(deform.cache_stats().prepared, 7u);
}

}  // namespace
}  // namespace tourmap::api
