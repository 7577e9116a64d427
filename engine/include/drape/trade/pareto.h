#pragma once
// The Pareto front of a speed/accuracy trade: the points that no other point beats on both costs at once.
#include <utility>
#include <vector>

namespace drape::trade {

// For each point (cost a, cost b; both smaller is better), whether it is on the front: no other point has a and b
// at most its own with one of them smaller. Equal points are all on the front.
std::vector<bool> paretoFront(const std::vector<std::pair<double, double>>& points);

}  // namespace drape::trade
