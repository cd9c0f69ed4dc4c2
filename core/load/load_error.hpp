#pragma once
// The one error every loader throws: what went wrong and where (file, line or record).

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

}  // namespace tourmap::load
