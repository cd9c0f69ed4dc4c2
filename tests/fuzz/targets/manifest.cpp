// Data manifests (store/manifest: parse_manifest, run by `tourmap import manifest`).
// Clean error: std::invalid_argument ("naming the entry and field").

#include "fuzz_common.hpp"

#include "store/manifest.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::store;
  try {
    const Manifest m = parse_manifest(std::string(reinterpret_cast<const char*>(data), size), "/data");
    // Relative paths are resolved against the data directory.
    for (const auto& p : m.pois)
      FUZZ_CHECK(!p.file.empty() && p.file[0] == '/');
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
