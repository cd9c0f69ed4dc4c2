// Line-ordered station CSV imports (core/load/metro_line_csv: load_metro_line_csv, as the
// importer calls it, on a file rewritten for every input). Clean error: load::LoadError.

#include "fuzz_common.hpp"
#include "support/check_metro.hpp"

#include "load/load_error.hpp"
#include "load/metro_load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  static const std::string path = fuzz::ScratchDir::get().path() / "line.csv";
  fuzz::ScratchDir::get().write("line.csv", fuzz::as_view(data, size));
  try {
    fuzz::check_metro(load::load_metro_line_csv(path));
  } catch (const load::LoadError&) {
  }
  return 0;
}
