#include "load/csv.hpp"

#include "load/load_error.hpp"
#include "load/strings.hpp"
#include "util/stop.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace tourmap::load {
namespace {

[[noreturn]] void missing_column(const std::string& source, std::span<const std::string_view> names) {
  throw LoadError(source + " line 1", "missing column '" + std::string(names.front()) + "'");
}

}  // namespace

std::optional<std::size_t> find_csv_column(const std::vector<std::string>& header,
                                           std::span<const std::string_view> names) {
  for (auto name : names)
    for (std::size_t c = 0; c < header.size(); ++c)
      if (iequals(trim(header[c]), name)) return c;
  return std::nullopt;
}

// --- CsvReader ---

CsvReader::CsvReader(std::string_view text, std::string source, const ImportLimits& limits)
    : text_(text),
      source_(std::move(source)),
      max_fields_(limits.max_csv_fields),
      max_field_bytes_(limits.max_csv_field_bytes) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
  bool blank = false;
  while (read_record(blank)) {
    if (blank) continue;
    header_ = std::move(row_);
    row_.clear();
    return;
  }
  throw LoadError(source_, "empty CSV file (no header)");
}

std::string CsvReader::where() const { return source_ + " line " + std::to_string(row_line_); }

std::size_t CsvReader::column(std::span<const std::string_view> names) const {
  if (auto c = find_column(names)) return *c;
  missing_column(source_, names);
}

bool CsvReader::next() {
  bool blank = false;
  while (read_record(blank)) {
    if (blank) continue;
    if (row_.size() != header_.size())
      throw LoadError(where(), "expected " + std::to_string(header_.size()) + " fields, found " +
                                   std::to_string(row_.size()));
    return true;
  }
  row_.clear();
  return false;
}

bool CsvReader::read_record(bool& blank) {
  if ((records_++ & 1023) == 0) util::check_stop();  // the first record, then every 1,024
  row_.clear();
  blank = false;
  if (pos_ >= text_.size()) return false;
  row_line_ = line_;
  std::string field;
  bool in_quotes = false, field_started = false, any_in_record = false;

  // "field 3 ('name')" once the header is known.
  auto field_name = [&] {
    auto name = "field " + std::to_string(row_.size() + 1);
    if (row_.size() < header_.size()) name += " ('" + header_[row_.size()].substr(0, 64) + "')";
    return name;
  };
  auto end_field = [&] {
    if (row_.size() >= max_fields_)
      check_limit(row_.size() + 1, max_fields_, "max_csv_fields", where(), "fields in a row");
    row_.push_back(std::move(field));
    field.clear();
    field_started = false;
  };
  auto push = [&](char ch) {
    if (field.size() >= max_field_bytes_)
      check_limit(field.size() + 1, max_field_bytes_, "max_csv_field_bytes", where(), "bytes in " + field_name());
    field.push_back(ch);
  };

  const std::size_t n = text_.size();
  for (; pos_ < n; ++pos_) {
    const char ch = text_[pos_];
    if (in_quotes) {
      if (ch == '"') {
        if (pos_ + 1 < n && text_[pos_ + 1] == '"') {
          push('"');
          ++pos_;
        } else {
          in_quotes = false;
        }
      } else {
        if (ch == '\n') ++line_;
        push(ch);
      }
      continue;
    }
    switch (ch) {
      case '"':
        if (!field_started || field.empty()) {
          in_quotes = true;
          field_started = true;
          any_in_record = true;
        } else {
          push(ch);  // a stray quote inside an unquoted field is kept literally
        }
        break;
      case ',':
        end_field();
        any_in_record = true;
        break;
      case '\r':
        break;
      case '\n':
        end_field();
        ++pos_;
        ++line_;
        blank = row_.size() == 1 && row_[0].empty() && !any_in_record;
        return true;
      default:
        push(ch);
        field_started = true;
        any_in_record = true;
    }
  }
  if (in_quotes) throw LoadError(where(), "unterminated quoted field");
  if (!any_in_record && field.empty()) return false;  // the text ended with a line break (or '\r')
  end_field();
  return true;
}

// --- CsvTable ---

std::size_t CsvTable::column(std::span<const std::string_view> names) const {
  if (auto c = find_column(names)) return *c;
  missing_column(source, names);
}

std::string CsvTable::where(std::size_t r) const {
  return source + " line " + std::to_string(row_lines.at(r));
}

CsvTable parse_csv(std::string_view text, const std::string& source, const ImportLimits& limits) {
  CsvReader reader(text, source, limits);
  CsvTable table;
  table.source = source;
  table.header = reader.header();
  while (reader.next()) {
    table.rows.push_back(std::move(reader.row()));
    table.row_lines.push_back(reader.line());
  }
  return table;
}

bool is_null_field(std::string_view field) {
  field = trim(field);
  return field.empty() || field == "NULL" || field == "null";
}

double parse_number(std::string_view field, const std::string& where, std::string_view column) {
  auto s = trim(field);
  double value = 0.0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(value))
    throw LoadError(where, "column '" + std::string(column) + "' is not a number: '" + std::string(s) + "'");
  return value;
}

}  // namespace tourmap::load
