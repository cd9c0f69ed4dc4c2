#pragma once
// What a deformation asks for, in map units: a target scale per road edge (focus regions,
// eq. 4.8/4.9) and guide vertices with targets (mental and destination maps, eq. 4.6/4.7).

#include "deform/planar.hpp"

#include <vector>

namespace tourmap::deform {

struct Guide {
  std::uint32_t node = 0;  // road node index
  XY target;
};

struct Targets {
  std::vector<double> edge_scale;  // one per road edge (empty: all 1)
  std::vector<Guide> guides;
};

// Objective weights (eq. 4.5, plus the guide term). Defaults are the ones documented in
// api/openapi.yaml; they were chosen on the shared road networks (see the deform benchmark).
struct Weights {
  double road = 1.0;     // w_RE, road edges (eq. 4.2 / 4.9)
  double quad = 0.3;     // w_QE, quad shape incl. support edges (eq. 4.3)
  double smooth = 0.5;   // w_SM, Laplacian smoothing (eq. 4.4)
  double guide = 100.0;  // w_GV, guide vertices (eq. 4.7)
};

enum class Boundary {
  fixed,    // the frame's outline stays put (focus maps: the focus grows at the context's expense)
  sliding,  // outline vertices move along the outline only; corners stay
};

// Unweighted road-edge residual plus unweighted guide residual (paper 4.5 "Evaluation"):
// the same measure for every method, computed from deformed road node positions.
double residue(const PlanarNetwork& net, const Targets& targets, const std::vector<XY>& deformed_nodes);

}  // namespace tourmap::deform
