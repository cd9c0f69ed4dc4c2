#include "load/csv.hpp"

#include "load/load_error.hpp"
#include "load/strings.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

namespace tourmap::load {

std::optional<std::size_t> CsvTable::find_column(std::span<const std::string_view> names) const {
  for (auto name : names)
    for (std::size_t c = 0; c < header.size(); ++c)
      if (iequals(trim(header[c]), name)) return c;
  return std::nullopt;
}

std::size_t CsvTable::column(std::span<const std::string_view> names) const {
  if (auto c = find_column(names)) return *c;
  throw LoadError(source + " line 1", "missing column '" + std::string(names.front()) + "'");
}

std::string CsvTable::where(std::size_t r) const {
  return source + " line " + std::to_string(row_lines.at(r));
}

CsvTable parse_csv(std::string_view text, const std::string& source) {
  CsvTable table;
  table.source = source;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);

  std::vector<std::string> record;
  std::string field;
  std::size_t line = 1, record_line = 1;
  bool in_quotes = false, field_started = false, any_in_record = false;

  auto end_field = [&] {
    record.push_back(std::move(field));
    field.clear();
    field_started = false;
  };
  auto end_record = [&] {
    end_field();
    bool blank = record.size() == 1 && record[0].empty() && !any_in_record;
    if (!blank) {
      if (table.header.empty()) {
        table.header = std::move(record);
      } else if (record.size() != table.header.size()) {
        throw LoadError(source + " line " + std::to_string(record_line),
                        "expected " + std::to_string(table.header.size()) + " fields, found " +
                            std::to_string(record.size()));
      } else {
        table.rows.push_back(std::move(record));
        table.row_lines.push_back(record_line);
      }
    }
    record.clear();
    any_in_record = false;
  };

  for (std::size_t i = 0; i < text.size(); ++i) {
    char ch = text[i];
    if (in_quotes) {
      if (ch == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field.push_back('"');
          ++i;
        } else {
          in_quotes = false;
        }
      } else {
        if (ch == '\n') ++line;
        field.push_back(ch);
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
          field.push_back(ch);  // a stray quote inside an unquoted field is kept literally
        }
        break;
      case ',':
        end_field();
        any_in_record = true;
        break;
      case '\r':
        break;
      case '\n':
        end_record();
        ++line;
        record_line = line;
        break;
      default:
        field.push_back(ch);
        field_started = true;
        any_in_record = true;
    }
  }
  if (in_quotes) throw LoadError(source + " line " + std::to_string(record_line), "unterminated quoted field");
  if (any_in_record || !field.empty()) end_record();
  if (table.header.empty()) throw LoadError(source, "empty CSV file (no header)");
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
