// Data manifests (store/manifest: parse_manifest, run by `tourmap import manifest`), with the
// cities' name rules (store/metro_rules, load/name_rules).
// Clean error: std::invalid_argument ("naming the entry and field").
// Properties: relative paths are resolved; valid rules clean any name idempotently.

#include "fuzz_common.hpp"

#include "load/name_rules.hpp"
#include "store/manifest.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::store;
  try {
    const Manifest m = parse_manifest(std::string(reinterpret_cast<const char*>(data), size), "/data");
    // Relative paths are resolved against the data directory.
    for (const auto& p : m.pois)
      FUZZ_CHECK(!p.file.empty() && p.file[0] == '/');
    for (const auto& metro : m.metros) {
      std::vector<std::string> names = {"U Alt-Tegel (Berlin) [U8]", "S+U Wittenau (Bln)", "PRA\xC3\x87" "A DE ESPANHA",
                                        "Addison (Blue)", "  A  B  ", "\xC3"};
      for (const auto& [from, to] : metro.rules.rename) names.insert(names.end(), {from, to});
      for (const auto& f : metro.files) names.push_back(f);  // arbitrary fuzzed text
      for (const auto& name : names) {
        const auto once = tourmap::load::clean_name(name, metro.rules);
        FUZZ_CHECK(tourmap::load::clean_name(once, metro.rules) == once);
      }
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
