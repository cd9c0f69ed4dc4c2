#pragma once
// A linear program (a MipModel without integer columns) solved by CLP's primal simplex in this
// process. CBC adds only its set-up to a pure LP, and that set-up dominated: on the first
// spacing programs (metro/station_spacing.hpp) CBC took 0.5 s on Vienna and 25 s on London
// where CLP's primal simplex took 0.07 s and 2.2 s.

#include "metro/mip_model.hpp"

namespace tourmap::metro {

// status "optimal", "time_limit", "infeasible" or "error"; x set for "optimal" only. Integer
// marks on columns are ignored (the relaxation is solved).
MipResult solve_lp_with_clp(const MipModel& m, double time_limit_s);

}  // namespace tourmap::metro
