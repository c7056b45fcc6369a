// qp/ipopt_program.hpp — what the step solvers' Ipopt programs (qp/ipopt.cpp,
// qp/friction_ipopt.cpp) share: Ipopt's status and the solution's first n variables X,
// kept when Ipopt finishes; Ipopt's infinity; a matrix's lower triangle as Hessian entries.
#pragma once

#include <coin/IpTNLP.hpp>

#include <Eigen/Core>
#include <vector>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

constexpr double kIpoptInfinity = 2e19;  // Ipopt reads |bound| ≥ 1e19 as no bound

// Lower-triangle entries (row ≥ col) of M, shifted by `offset`, scaled by `factor`.
inline void lower_triangle(const SparseMatrix& M, int offset, double factor, std::vector<Ipopt::Index>& rows,
                           std::vector<Ipopt::Index>& cols, std::vector<double>& vals) {
  for (int j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it)
      if (it.row() >= j) {
        rows.push_back(offset + static_cast<Ipopt::Index>(it.row()));
        cols.push_back(offset + j);
        vals.push_back(factor * it.value());
      }
}

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
