#pragma once
// Where the shared sample data is: $TOURMAP_DATA_DIR, else the build's default (../shared/data).

#include <string>

namespace tourmap::test {

std::string data_dir();
// data_dir() + "/" + relative
std::string data_file(const std::string& relative);

}  // namespace tourmap::test
