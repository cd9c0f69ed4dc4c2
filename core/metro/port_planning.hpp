#pragma once
// Ports for route_octilinear: which of the 8 octilinear directions each edge leaves a station
// by. Distinct directions, in the circular order of the edges' geographic directions (an
// octilinear layout keeps the map's topology only if every station keeps that order).

#include "metro/grid_chains.hpp"

#include <array>
#include <utility>
#include <vector>

namespace tourmap::metro::octi {

// The ports a station's edges should use: distinct octilinear directions, in the circular
// order of the edges' geographic directions, as close to those directions as possible (the
// least total angular deviation over every order-keeping choice). Up to 8 edges; with more,
// every port is -1 (no plan). `angles` in radians, ports 0..7 counter-clockwise from east.
std::vector<int> plan_ports(const std::vector<double>& angles);

// The planned port of every chain at its front and back anchor (plan_ports per anchor).
std::vector<std::array<int, 2>> plan_chain_ports(const LayoutGraph& g, const std::vector<Chain>& chains);

// Per node: the geographic angles of the chains that end there (front and back ends).
std::vector<std::vector<double>> chain_end_angles(const LayoutGraph& g, const std::vector<Chain>& chains);

// Whether leaving a station through port d (geographic direction theta) keeps the ports in the
// circular order of the geographic directions, with enough free ports in every gap for the
// edges still to be routed there (so that no later edge is left without an in-order port).
// `taken`: (port, geographic angle) of the station's routed edges; `end_angles`: the angles of
// all its edges (chain_end_angles), routed or not.
bool keeps_circular_order(const std::vector<std::pair<int, double>>& taken, const std::vector<double>& end_angles,
                          double theta, int d);

}  // namespace tourmap::metro::octi
