// trajectory_fixtures.hpp — comparing two runs step by step (the friction tests).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace cdyn::testing {

// max over the steps of max |U_a − U_b| on the full displacement (a Step has U_full).
template <class Step>
double max_abs_difference(const std::vector<Step>& a, const std::vector<Step>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, (a[k].U_full - b[k].U_full).template lpNorm<Eigen::Infinity>());
  return d;
}

}  // namespace cdyn::testing
