#pragma once
// The binary answer of POST /api/v1/deform/{app} with "output": {"roads": "positions"} and
// "Accept: application/octet-stream" (api/openapi.yaml, DeformPositionsBinary): the JSON answer
// without "positions", then the positions as float32 offsets from a float64 origin, so that a
// client copies them into a typed array instead of parsing 56,000 x 2 numbers from text.
//
//   offset  size  little-endian
//   0       4     "TMDP" (ASCII)
//   4       4     uint32 format version: 1
//   8       4     uint32 J: bytes of JSON
//   12      4     uint32 P: points (the network's nodes, in its node order)
//   16      8     float64 origin longitude, degrees
//   24      8     float64 origin latitude, degrees
//   32      J     the JSON answer (UTF-8) without "positions"
//   32 + J  0-3   zero bytes, up to a multiple of 4
//   then    8 P   float32 pairs: longitude - origin, latitude - origin (degrees)
//
// The origin is the middle of the points' bounding box: float32 offsets over a network a few
// tenths of a degree across keep positions to a few millimetres.

#include "geo/lonlat.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::api {

inline constexpr char kPositionsMagic[4] = {'T', 'M', 'D', 'P'};
inline constexpr std::uint32_t kPositionsVersion = 1;

std::string encode_positions_binary(std::string_view json, const std::vector<geo::LonLat>& points);

// Whether an Accept header asks for application/octet-stream: it names it with q > 0, and
// application/json, if named, with no higher q (wildcards such as */* count for neither).
bool accepts_octet_stream(std::string_view accept);

}  // namespace tourmap::api
