#pragma once
// Representative pose selection (sec. 3.4.1): poses are points in a pose space reduced by
// classical MDS (9 dimensions, after Assa et al.); a clustering stage merges pose groups that
// have any two points within d, a partitioning stage splits groups whose bounding-box diagonal
// exceeds 1.5 d at the median of their longest axis, and each final group is represented by
// the pose closest to its bounding-box centre.

#include "crowd/skinned_model.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace tourmap::crowd {

// Clustering then partitioning of the rows of `points` (n x dims, n <= 20000: the clustering
// stage scans all pairs, which for the few hundred poses of an animation is cheaper than
// building the kd-tree the paper suggests). Groups hold ascending row indices and are ordered
// by their representative. Throws std::invalid_argument for d < 0 or non-finite input.
std::vector<std::vector<int>> group_poses(const Eigen::MatrixXd& points, double d);

// The member closest to the centre of the group's bounding box (lowest index on ties).
int representative(const Eigen::MatrixXd& points, const std::vector<int>& group);

// Pose distance used for selection, in model length units: the largest distance between the
// skinned positions of the same vertex in the two poses, over up to `max_samples` evenly spaced
// vertices, after mapping each pose into the frame the main root joint has in pose 0 (removing
// the travel and turning the root carries) and subtracting the sample's centroid (removing
// travel carried elsewhere). "Two poses are within d" then means "no vertex is more than d
// apart", the same kind of bound as the geometric simplification error, independent of the
// rig and of the mesh resolution. (The RMS over vertices was tried first: it is ~3x smaller,
// so with d = 20% of the diagonal almost every clip collapsed to one representative.)
// The max is a metric but not Euclidean: classical MDS keeps its positive spectrum.
inline constexpr std::size_t kPoseDistanceSamples = 2000;
Eigen::MatrixXd pose_distances(const SkinnedModel& model, int animation,
                               std::size_t max_samples = kPoseDistanceSamples);

struct PoseSelection {
  std::vector<int> representatives;      // pose indices, ascending; one per group
  double d = 0;                          // grouping distance (model units)
  std::vector<std::vector<int>> groups;  // groups[i] is represented by representatives[i]
  Eigen::MatrixXd points;                // poses in the reduced space (pose count x dims)
  std::size_t pose_count = 0;
  std::size_t sample_vertices = 0;  // vertices the pose distance used
};

// d = d_fraction x the bind-pose bounding-box diagonal (the paper uses 10%-30%).
PoseSelection select_poses(const SkinnedModel& model, int animation, float d_fraction = 0.2f, int dims = 9);

}  // namespace tourmap::crowd
