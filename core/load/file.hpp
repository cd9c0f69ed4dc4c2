#pragma once
// Whole-file reads for the loaders (the only place core touches the file system).

#include <string>

namespace tourmap::load {

// Reads a file into memory; throws LoadError naming the path when it cannot.
std::string read_file(const std::string& path);

// The last path component, used to name sources in errors and provenance.
std::string file_name(const std::string& path);

}  // namespace tourmap::load
