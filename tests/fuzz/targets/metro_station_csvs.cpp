// Station / line / connection CSV triple imports (core/load/metro_station_csvs:
// load_metro_station_csvs, as the importer calls it). The input holds the three files
// separated by lines "====" (stations, lines, connections); each is rewritten for every input.
// Clean error: load::LoadError.

#include "fuzz_common.hpp"
#include "support/check_metro.hpp"

#include "load/load_error.hpp"
#include "load/metro_load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  auto& dir = fuzz::ScratchDir::get();
  auto parts = fuzz::split(fuzz::as_view(data, size), "\n====\n", 3);
  parts.resize(3);
  const std::string stations = dir.write("stations.csv", parts[0]);
  const std::string lines = dir.write("lines.csv", parts[1]);
  const std::string connections = dir.write("connections.csv", parts[2]);
  try {
    fuzz::check_metro(load::load_metro_station_csvs(stations, lines, connections));
  } catch (const load::LoadError&) {
  }
  return 0;
}
