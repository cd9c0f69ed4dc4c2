#pragma once
// Octilinear polylines between two points with as few bends as possible, and the polyline
// arithmetic the bend reduction (metro/bend_reduction.hpp) needs: bends, length, a point at an
// arc length, the piece between two arc lengths.
//
// Between two points p and q there is a straight octilinear line when q - p runs at a multiple
// of 45 degrees; otherwise q - p = a * d_i + b * d_j (a, b > 0) for 6 pairs of the 8 octilinear
// directions (one pair 45 degrees apart, two 90, three 135), each drawn with one bend in two
// orders, and a symmetric Z (two bends) along the 45-degree pair.

#include "metro/layout_graph.hpp"

#include <array>
#include <vector>

namespace tourmap::metro {

// The 8 directions counter-clockwise from east, unnormalised so that multiples stay exact.
inline constexpr std::array<XY, 8> kOctants = {{{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};

// The direction index (0..7) of v when it runs within `eps` (absolute, on the coordinates) of a
// multiple of 45 degrees, else -1 (also for a zero vector).
int octant_of(XY v, double eps);

struct OctilinearShape {
  std::vector<XY> corners;  // from p to q, p and q included
  int bends = 0;
  int turn45 = 0;           // sum of the turns at the bends, in 45-degree steps
};

// Every shape described above (the straight line alone when there is one).
std::vector<OctilinearShape> octilinear_shapes(XY p, XY q, double eps);

double polyline_length(const std::vector<XY>& pts);

// Direction changes along the polyline (turns above `min_turn_rad`; zero-length pieces skipped).
int polyline_bends(const std::vector<XY>& pts, double min_turn_rad = 0.0175);

// The polyline with repeated points and vertices on a straight run dropped.
std::vector<XY> simplify_polyline(const std::vector<XY>& pts, double eps);

// The point at arc length s (clamped to the polyline).
XY point_at_length(const std::vector<XY>& pts, double s);

// The points at the inner arc lengths arcs[1 .. n-2] (sorted; the ends are skipped), in one sweep.
std::vector<XY> points_at_lengths(const std::vector<XY>& pts, const std::vector<double>& arcs);

// The part of the polyline between arc lengths s0 < s1, both ends included.
std::vector<XY> polyline_between(const std::vector<XY>& pts, double s0, double s1);

}  // namespace tourmap::metro
