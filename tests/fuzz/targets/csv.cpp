// RFC 4180 CSV (core/load/csv: parse_csv) with the column lookups and number parsing every CSV
// loader does on its rows (find_column, column, where, is_null_field, parse_number).
// Clean error: load::LoadError.

#include "fuzz_common.hpp"

#include "load/csv.hpp"
#include "load/load_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap::load;
  try {
    const CsvTable t = parse_csv(tourmap::fuzz::as_view(data, size), "fuzz.csv");
    FUZZ_CHECK(!t.header.empty() && t.rows.size() == t.row_lines.size());
    const auto lon = t.find_column({"lon", "lng", "longitude"});
    (void)t.find_column({"name"});
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      FUZZ_CHECK(t.rows[r].size() == t.header.size());  // promised by parse_csv
      const auto where = t.where(r);
      for (const auto& field : t.rows[r]) {
        (void)is_null_field(field);
        try {
          (void)parse_number(field, where, "x");
        } catch (const LoadError&) {
        }
      }
      if (lon) (void)is_null_field(t.rows[r][*lon]);
    }
    (void)t.column({"id"});
  } catch (const LoadError&) {
  }
  return 0;
}
