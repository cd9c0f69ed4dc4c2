#pragma once
// Option parsing shared by the `tourmap` subcommands: command line first, then TOURMAP_*
// environment variables (--db is TOURMAP_DB, --data-dir is TOURMAP_DATA_DIR, ...).

#include "config.hpp"

#include <boost/program_options.hpp>

#include <string>
#include <vector>

namespace tourmap::server {

boost::program_options::variables_map parse_options(const boost::program_options::options_description& desc,
                                                    const boost::program_options::positional_options_description& pos,
                                                    const std::vector<std::string>& args);
boost::program_options::options_description db_options(Config& c);

// `tourmap keys create|list|revoke`: API keys for the write endpoints.
int cmd_keys(const std::vector<std::string>& args);

}  // namespace tourmap::server
