// qp/ipopt_program.hpp — what the step solvers' Ipopt programs (qp/ipopt.cpp,
// qp/friction_ipopt.cpp) share: Ipopt's status and the solution's first n variables X,
// kept when Ipopt finishes.
#pragma once

#include <coin/IpTNLP.hpp>

#include <Eigen/Core>

namespace cdyn {

class IpoptProgram : public Ipopt::TNLP {
 public:
  explicit IpoptProgram(int solution_size) : solution_size_(solution_size) {}

  void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index, const Ipopt::Number* x, const Ipopt::Number*,
                         const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    status_ = status;
    X_ = Eigen::Map<const Eigen::VectorXd>(x, solution_size_);
  }

  Eigen::VectorXd X_;
  Ipopt::SolverReturn status_ = Ipopt::INTERNAL_ERROR;

 private:
  int solution_size_;
};

}  // namespace cdyn
