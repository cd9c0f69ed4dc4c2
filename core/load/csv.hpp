#pragma once
// RFC 4180 CSV: quoted fields with embedded commas, quotes and newlines; CRLF or LF; UTF-8 BOM.
// Written here because none of the project's libraries parses CSV.
//
// Memory stays bounded whatever the input: the reader streams one record at a time, and a
// record may hold at most ImportLimits::max_csv_fields fields of at most max_csv_field_bytes
// bytes each (a file of nothing but commas is one huge record): beyond either, LimitExceeded.

#include "load/import_limits.hpp"

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::load {

// Index of the first column of `header` whose name matches one of `names` (case-insensitive).
std::optional<std::size_t> find_csv_column(const std::vector<std::string>& header,
                                           std::span<const std::string_view> names);

// Streams the records of a CSV text: the header first (the first non-blank record), then one
// row per next(). Blank lines are skipped. Polls util::check_stop() at the first line and every
// 1,024 lines.
class CsvReader {
 public:
  // Reads the header. Throws LoadError on an empty file (no header), LimitExceeded on a header
  // beyond the limits.
  CsvReader(std::string_view text, std::string source, const ImportLimits& limits = {});

  const std::string& source() const { return source_; }
  const std::vector<std::string>& header() const { return header_; }

  // Reads the next row; false at the end of the text. Throws LoadError on an unterminated
  // quote or a row whose field count differs from the header, LimitExceeded on a row or field
  // beyond the limits.
  bool next();
  // The current row (after next() returned true): header().size() fields.
  const std::vector<std::string>& row() const { return row_; }
  std::vector<std::string>& row() { return row_; }
  // 1-based line where the current row starts.
  std::size_t line() const { return row_line_; }
  // "file line N" for errors about the current row.
  std::string where() const;

  std::optional<std::size_t> find_column(std::span<const std::string_view> names) const {
    return find_csv_column(header_, names);
  }
  std::optional<std::size_t> find_column(std::initializer_list<std::string_view> names) const {
    return find_column(std::span(names.begin(), names.size()));
  }
  // Same, but throws LoadError "missing column" naming the first candidate.
  std::size_t column(std::span<const std::string_view> names) const;
  std::size_t column(std::initializer_list<std::string_view> names) const {
    return column(std::span(names.begin(), names.size()));
  }

 private:
  // Reads one record into row_ (false at the end of the text); `blank` tells an empty line.
  bool read_record(bool& blank);

  std::string_view text_;
  std::string source_;
  std::size_t max_fields_, max_field_bytes_;
  std::size_t pos_ = 0, line_ = 1, row_line_ = 1, records_ = 0;
  std::vector<std::string> header_, row_;
};

struct CsvTable {
  std::string source;  // file name, for errors
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // every row has header.size() fields
  std::vector<std::size_t> row_lines;          // 1-based line where each row starts

  // Index of the first column whose name matches one of `names` (case-insensitive).
  std::optional<std::size_t> find_column(std::span<const std::string_view> names) const {
    return find_csv_column(header, names);
  }
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

// The whole table at once (through CsvReader, so with its limits; the rows themselves are not
// limited: the loaders stream with CsvReader instead). Throws like CsvReader.
CsvTable parse_csv(std::string_view text, const std::string& source, const ImportLimits& limits = {});

// Field helpers: "NULL" and "" count as absent.
bool is_null_field(std::string_view field);
// Parses a finite double; throws LoadError naming `where` and `column` otherwise.
double parse_number(std::string_view field, const std::string& where, std::string_view column);

}  // namespace tourmap::load
