#pragma once
// The one error every loader throws: what went wrong and where (file, line or record).

#include <cstdint>
#include <stdexcept>
#include <string>

namespace tourmap::load {

class LoadError : public std::runtime_error {
 public:
  // `where` names the file and the record, e.g. "london.connections.csv line 12".
  LoadError(const std::string& where, const std::string& what)
      : std::runtime_error(where + ": " + what), where_(where) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

// A source beyond one of the import limits (import_limits.hpp): too many records, too long a
// text, too much (decompressed) data. Thrown at the first excess, before the rest is read.
// The HTTP layer answers it with 413, naming limit() and value().
class LimitExceeded : public LoadError {
 public:
  // `limit` is the ImportLimits member's name ("max_pois"), `value` its value; the message is
  // "<where>: <what> (limit <limit> = <value>)".
  LimitExceeded(const std::string& where, const std::string& what, std::string limit, std::uint64_t value)
      : LoadError(where, what + " (limit " + limit + " = " + std::to_string(value) + ")"),
        limit_(std::move(limit)),
        value_(value) {}
  // Stable snake_case name of the limit, e.g. "max_pois", "max_csv_field_bytes".
  const std::string& limit() const { return limit_; }
  // The limit's value (a count, or bytes for the *_bytes limits).
  std::uint64_t value() const { return value_; }

 private:
  std::string limit_;
  std::uint64_t value_;
};

}  // namespace tourmap::load
