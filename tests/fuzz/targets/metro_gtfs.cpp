// GTFS feed imports (core/load/metro_gtfs: load_metro_gtfs over a folder, as the importer
// calls it; the streamed CSV reader under it). The input holds the feed's five files separated
// by lines "====" (stops, routes, trips, stop_times, shapes); each is rewritten for every
// input, an absent part leaves its file empty. Clean error: load::LoadError.

#include "fuzz_common.hpp"
#include "support/check_metro.hpp"

#include "load/load_error.hpp"
#include "load/metro_gtfs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  auto& dir = fuzz::ScratchDir::get();
  auto parts = fuzz::split(fuzz::as_view(data, size), "\n====\n", 5);
  parts.resize(5);
  const char* files[] = {"feed/stops.txt", "feed/routes.txt", "feed/trips.txt", "feed/stop_times.txt", "feed/shapes.txt"};
  std::string folder;
  for (int i = 0; i < 5; ++i) folder = dir.write(files[i], parts[i]);
  folder = folder.substr(0, folder.rfind('/'));
  try {
    fuzz::check_metro(load::load_metro_gtfs(folder, {}));
  } catch (const load::LoadError&) {
  }
  return 0;
}
