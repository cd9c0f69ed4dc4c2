#pragma once
// The JSON form of a city's metro rules lives in core (load/metro_rules_json.hpp), so that the
// benchmarks, which link only core, clean names as the import does; the store's callers use it
// by these names.

#include "load/metro_rules_json.hpp"

namespace tourmap::store {

using load::metro_rules_json;
using load::parse_metro_rules;

}  // namespace tourmap::store
