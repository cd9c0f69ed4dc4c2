#pragma once
// Loop subdivision of a skinned model: each level splits every triangle into 4, moving old and
// new vertices with Loop's smoothing stencils, so a high-resolution variant carries real
// curvature (the paper's characters have 73K-110K triangles; a simplifier could trivially undo
// flat midpoint subdivision, which would make the LOD benchmark unfair). Skin influences and
// colours are interpolated with the same stencils; normals are recomputed.

#include "crowd/skinned_model.hpp"

namespace tourmap::crowd {

// `levels` in [0, 6]; throws std::invalid_argument beyond that or past 2^26 triangles, or if
// the model's arrays are inconsistent. Skeleton and animations are copied unchanged.
SkinnedModel subdivide(const SkinnedModel& model, int levels);

}  // namespace tourmap::crowd
