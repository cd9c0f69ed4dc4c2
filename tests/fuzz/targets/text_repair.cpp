// Mojibake repair of imported names (core/load/text_repair: repair_mojibake, is_valid_utf8).
// No error path: it must return for any bytes. Properties: valid UTF-8 stays valid UTF-8, and
// a repair only ever shortens the text.

#include "fuzz_common.hpp"

#include "load/text_repair.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::load;
  const std::string_view in = tourmap::fuzz::as_view(data, size);
  const bool valid = is_valid_utf8(in);
  const std::string out = repair_mojibake(in);
  FUZZ_CHECK(out.size() <= in.size());
  FUZZ_CHECK(!valid || is_valid_utf8(out));
  return 0;
}
