#pragma once
// The metro map endpoints (paper ch. 5): layouts, visual worth rasters and active POI clusters,
// with their caches: per city version the derived data and the geographic cluster tree; per
// (city version, parameters) the layout (also persisted in the store's result cache, since a
// large network takes seconds) and the layout-space cluster tree.

#include "catalog.hpp"
#include "http.hpp"
#include "lru_cache.hpp"
#include "metro_layout.hpp"
#include "single_flight.hpp"

#include "poi/cluster_tree.hpp"

#include <memory>

namespace tourmap::api {

struct MetroLimits {
  std::size_t max_raster_side = 512;
  std::size_t max_m = 100;
};

class MetroService {
 public:
  // Without `mip`, MIPs are solved in this process (tests, benchmarks); the server passes a
  // child-process solver so that no request outlives its deadline.
  explicit MetroService(Catalog& catalog, MipSolver mip = {}, MetroLimits limits = {});

  Response layout(const Request& req, bool post);
  Response visual_worth(const Request& req);
  Response clusters(const Request& req);

  std::shared_ptr<const CityMetroData> data_for(const std::string& city_id);
  std::shared_ptr<const CityLayout> layout_for(const CityMetroData& data, const LayoutRequest& req, bool* cached);

 private:
  std::shared_ptr<const poi::ClusterTree> tree_for(const std::string& key, const std::vector<geo::XY>& points,
                                                   const std::vector<double>& worth, const std::vector<bool>* skip);

  Catalog& catalog_;
  MipSolver mip_;
  MetroLimits limits_;
  LruCache<std::shared_ptr<const CityMetroData>> data_{16};
  LruCache<std::shared_ptr<const CityLayout>> layouts_{32};
  LruCache<std::shared_ptr<const poi::ClusterTree>> trees_{32};
  LruCache<std::shared_ptr<const std::vector<double>>> geo_worth_{16};
  SingleFlight<std::shared_ptr<const CityLayout>> layout_flight_;
  SingleFlight<std::shared_ptr<const poi::ClusterTree>> tree_flight_;
};

}  // namespace tourmap::api
