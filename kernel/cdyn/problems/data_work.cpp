// problems/data_work.cpp — the work of data in t over a step (data_work.hpp).
#include "cdyn/problems/data_work.hpp"

#include <cmath>

namespace cdyn {

double DataIncrement::work(const ConstrainedProblem& p, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction) const {
  double w = dL.size() ? -dL.dot(p.full(X)) : 0.0;
  for (Eigen::Index i = 0; i < reaction.size() && dlower.size(); ++i)
    w += reaction[i] * (reaction[i] > 0 ? dlower[i] : dupper[i]);
  return w;
}

DataIncrement data_increment(const ConstrainedProblem& p, double t0, double t1) {
  DataIncrement d;
  if (!p.load_is_constant) {
    d.dL = p.full_load(t1);  // (a copy: full_load returns its one-time cache)
    d.dL -= p.full_load(t0);
  }
  if (!p.bounds_are_constant()) {
    Eigen::VectorXd lo0, up0, lo1, up1;
    p.bounds(t0, lo0, up0);
    p.bounds(t1, lo1, up1);
    auto increment = [](const Eigen::VectorXd& a1, const Eigen::VectorXd& a0) {
      Eigen::VectorXd d = a1 - a0;
      for (Eigen::Index i = 0; i < d.size(); ++i)
        if (!std::isfinite(d[i])) d[i] = 0.0;
      return d;
    };
    d.dlower = increment(lo1, lo0);
    d.dupper = increment(up1, up0);
  }
  return d;
}

}  // namespace cdyn
