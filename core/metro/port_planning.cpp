#include "metro/port_planning.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

namespace tourmap::metro::octi {
namespace {

// Angle between a direction and a port, in radians (0..pi).
double deviation(double angle, int port) {
  double d = std::fmod(std::abs(angle - port * M_PI / 4), 2 * M_PI);
  return std::min(d, 2 * M_PI - d);
}

// How many of the pending edge directions lie strictly between a0 and a1 counter-clockwise
// (all of them when there is only one fixed direction).
int pending_between(const std::vector<double>& pending, double a0, double a1, bool only_one) {
  int due = 0;
  for (double a : pending) due += only_one || (a0 < a1 ? (a > a0 && a < a1) : (a > a0 || a < a1));
  return due;
}

}  // namespace

std::vector<int> plan_ports(const std::vector<double>& angles) {
  std::size_t k = angles.size();
  std::vector<int> best(k, -1);
  if (k == 0 || k > 8) return best;
  std::vector<std::size_t> order(k);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return angles[a] < angles[b]; });
  double best_cost = std::numeric_limits<double>::infinity();
  // Choose k of the 8 ports (a bit mask), then rotate which sorted edge gets the first one.
  for (unsigned mask = 0; mask < 256; ++mask) {
    if (std::popcount(mask) != static_cast<int>(k)) continue;
    std::vector<int> ports;
    for (int q = 0; q < 8; ++q)
      if (mask & (1u << q)) ports.push_back(q);
    for (std::size_t rot = 0; rot < k; ++rot) {
      double cost = 0;
      for (std::size_t i = 0; i < k; ++i) cost += deviation(angles[order[i]], ports[(i + rot) % k]);
      if (cost < best_cost) {
        best_cost = cost;
        for (std::size_t i = 0; i < k; ++i) best[order[i]] = ports[(i + rot) % k];
      }
    }
  }
  return best;
}

std::vector<std::array<int, 2>> plan_chain_ports(const LayoutGraph& g, const std::vector<Chain>& chains) {
  std::vector<std::array<int, 2>> planned(chains.size(), {-1, -1});  // port at front / back anchor
  std::vector<std::vector<std::pair<int, bool>>> ends(g.pos.size());  // (chain, at its front)
  for (int ci = 0; ci < static_cast<int>(chains.size()); ++ci) {
    ends[chains[ci].nodes.front()].push_back({ci, true});
    ends[chains[ci].nodes.back()].push_back({ci, false});
  }
  for (const auto& at_v : ends) {
    std::vector<double> angles;
    for (auto [ci, front] : at_v) angles.push_back(end_angle(g, chains[ci], front));
    auto ports = plan_ports(angles);
    for (std::size_t i = 0; i < at_v.size(); ++i) planned[at_v[i].first][at_v[i].second ? 0 : 1] = ports[i];
  }
  return planned;
}

std::vector<std::vector<double>> chain_end_angles(const LayoutGraph& g, const std::vector<Chain>& chains) {
  std::vector<std::vector<double>> angles(g.pos.size());
  for (const auto& c : chains) {
    angles[c.nodes.front()].push_back(end_angle(g, c, true));
    angles[c.nodes.back()].push_back(end_angle(g, c, false));
  }
  return angles;
}

bool keeps_circular_order(const std::vector<std::pair<int, double>>& taken, const std::vector<double>& end_angles,
                          double theta, int d) {
  std::vector<std::pair<double, int>> fixed;  // (angle, port)
  for (auto [port, angle] : taken) fixed.push_back({angle, port});
  fixed.push_back({theta, d});
  std::sort(fixed.begin(), fixed.end());
  std::vector<double> pending = end_angles;
  for (const auto& f : fixed)
    if (auto it = std::find(pending.begin(), pending.end(), f.first); it != pending.end()) pending.erase(it);
  int turns = 0;
  for (std::size_t i = 0; i < fixed.size(); ++i) {
    const auto [a0, p0] = fixed[i];
    const auto [a1, p1] = fixed[(i + 1) % fixed.size()];
    const int gap = fixed.size() == 1 ? 8 : (p1 - p0 + 8) % 8;  // ports counter-clockwise from p0 to p1
    turns += gap;
    const int due = pending_between(pending, a0, a1, fixed.size() == 1);  // pending edges between a0 and a1
    if (gap == 0 || gap - 1 < due) return false;
  }
  return turns == 8;  // once round: the ports are in the angles' cyclic order
}

}  // namespace tourmap::metro::octi
