#pragma once
// RFC 4180 CSV: quoted fields with embedded commas, quotes and newlines; CRLF or LF; UTF-8 BOM.
// Written here because none of the project's libraries parses CSV.

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::load {

struct CsvTable {
  std::string source;  // file name, for errors
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // every row has header.size() fields
  std::vector<std::size_t> row_lines;          // 1-based line where each row starts

  // Index of the first column whose name matches one of `names` (case-insensitive).
  std::optional<std::size_t> find_column(std::span<const std::string_view> names) const;
  std::optional<std::size_t> find_column(std::initializer_list<std::string_view> names) const {
    return find_column(std::span(names.begin(), names.size()));
  }
  // Same, but throws LoadError "missing column" naming the first candidate.
  std::size_t column(std::span<const std::string_view> names) const;
  std::size_t column(std::initializer_list<std::string_view> names) const {
    return column(std::span(names.begin(), names.size()));
  }
  // "file line N" for errors about row `r`.
  std::string where(std::size_t r) const;
};

// Throws LoadError on an unterminated quote or a row whose field count differs from the header.
CsvTable parse_csv(std::string_view text, const std::string& source);

// Field helpers: "NULL" and "" count as absent.
bool is_null_field(std::string_view field);
// Parses a finite double; throws LoadError naming `where` and `column` otherwise.
double parse_number(std::string_view field, const std::string& where, std::string_view column);

}  // namespace tourmap::load
