// LOOM line-graph GeoJSON imports (core/load/metro_loom: load_metro_loom, as the importer
// calls it, on a file rewritten for every input). Clean error: load::LoadError.

#include "fuzz_common.hpp"
#include "support/check_metro.hpp"

#include "load/load_error.hpp"
#include "load/metro_load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  static const std::string path = fuzz::ScratchDir::get().path() / "metro.json";
  fuzz::ScratchDir::get().write("metro.json", fuzz::as_view(data, size));
  try {
    fuzz::check_metro(load::load_metro_loom(path));
  } catch (const load::LoadError&) {
  }
  return 0;
}
