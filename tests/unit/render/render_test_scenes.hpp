#pragma once
// Small hand-made models and cluster hierarchies for the renderer tests (independent of the
// real hierarchy builder): boxes, a two-joint bar, and a median-split hierarchy whose parents
// reuse every other triangle of their children.

#include "crowd/cluster_hierarchy.hpp"
#include "crowd/lod_cut.hpp"
#include "crowd/skinned_model.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace tourmap::render::test {

using Rgba = std::array<std::uint8_t, 4>;

// A box centred at the origin, each face split into n x n quads (12 n^2 triangles), one joint,
// one identity pose (static). With `poses` > 1 it gets more identical poses and is no longer
// static (a "dynamic" object for occlusion culling).
crowd::SkinnedModel box_model(const crowd::Vec3& half_extent, Rgba color, int n = 4, int poses = 1);

// A bar along +x from 0 to 2 with a 0.2 x 0.2 section, 8 segments; joint 0 holds x < 1, joint 1
// x > 1 (x = 1 is shared half and half). Pose 0 is straight, pose 1 bends joint 1 by 90 degrees
// about +z around (1, 0, 0).
crowd::SkinnedModel bar_model(Rgba color);

// Linear blend skinning of one vertex on the CPU (eq. 3.1).
crowd::Vec3 skinned_position(const crowd::SkinnedModel& model, const crowd::Pose& pose, std::size_t vertex);

// A complete binary hierarchy with 2^levels leaves (median splits of triangle centroids);
// a parent keeps every other triangle of its subtree, error = 0.02 * diagonal * height, bounds
// over every pose.
crowd::ClusterHierarchy test_hierarchy(const crowd::SkinnedModel& model, int levels);

// Pixel (x, y) with y counted from the top of a bottom-up RGBA image.
Rgba pixel(const std::vector<std::uint8_t>& rgba, int width, int height, int x, int y_from_top);

// Where a world point lands: pixel column and row from the top.
std::array<int, 2> project_to_pixel(const crowd::CameraView& view, const crowd::Vec3& world);

// Pixels whose channels differ by more than `tolerance`.
std::size_t differing_pixels(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int tolerance = 0);

}  // namespace tourmap::render::test

namespace tourmap::render {
class EglContext;
}

namespace tourmap::render::test {

// One context for the whole test process, made current on the calling thread (never destroyed:
// tearing EGL down during static destruction is not worth the risk).
EglContext& shared_context();

}  // namespace tourmap::render::test
