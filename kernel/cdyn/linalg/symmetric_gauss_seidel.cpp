// linalg/symmetric_gauss_seidel.cpp — greedy colouring, the scaled triangles and their sweeps;
// see linalg/symmetric_gauss_seidel.hpp.
#include "cdyn/linalg/symmetric_gauss_seidel.hpp"

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/parallel.hpp"

namespace cdyn {

SymmetricGaussSeidel::SymmetricGaussSeidel(const SparseMatrix& S) {
  const int n = static_cast<int>(S.rows());
  if (S.cols() != n || !S.isCompressed()) throw InputError("symmetric Gauss-Seidel: S must be square and compressed");
  const Eigen::VectorXd D = S.diagonal();
  if (!(D.array() > 0.0).all()) throw NumericalError("symmetric Gauss-Seidel: S has a non-positive diagonal entry");
  sqrt_diagonal_ = D.cwiseSqrt();

  // Greedy colouring in the natural order: the smallest colour no coupled unknown has.
  colour_.assign(n, -1);
  std::vector<int> taken_by;  // taken_by[c] == i: a neighbour of i has colour c
  for (int i = 0; i < n; ++i) {
    for (SparseMatrix::InnerIterator it(S, i); it; ++it)
      if (colour_[it.row()] >= 0) taken_by[colour_[it.row()]] = i;
    int c = 0;
    while (c < static_cast<int>(taken_by.size()) && taken_by[c] == i) ++c;
    if (c == static_cast<int>(taken_by.size())) taken_by.push_back(-1);
    colour_[i] = c;
  }

  const int colours = static_cast<int>(taken_by.size());
  colour_start_.assign(colours + 1, 0);
  for (int i = 0; i < n; ++i) ++colour_start_[colour_[i] + 1];
  for (int c = 0; c < colours; ++c) colour_start_[c + 1] += colour_start_[c];
  rows_.resize(n);
  std::vector<int> next(colour_start_.begin(), colour_start_.end() - 1);
  for (int i = 0; i < n; ++i) rows_[next[colour_[i]]++] = i;
  position_.resize(n);
  for (int k = 0; k < n; ++k) position_[rows_[k]] = k;

  // The triangles of Ŝ row by row in sweep order (S symmetric: column i is row i).
  for (Triangle* t : {&lower_, &upper_}) {
    t->start.assign(1, 0);
    t->column.reserve(S.nonZeros() / 2);
    t->value.reserve(S.nonZeros() / 2);
  }
  for (int i : rows_) {
    for (SparseMatrix::InnerIterator it(S, i); it; ++it) {
      const int j = static_cast<int>(it.row());
      if (j == i) continue;
      Triangle& t = colour_[j] < colour_[i] ? lower_ : upper_;
      t.column.push_back(j);
      t.value.push_back(it.value() / (sqrt_diagonal_[i] * sqrt_diagonal_[j]));
    }
    lower_.start.push_back(static_cast<int>(lower_.column.size()));
    upper_.start.push_back(static_cast<int>(upper_.column.size()));
  }
}

// In both sweeps the rows of one colour do not depend on each other: each is a gather
// of the finished values of other colours, and the loop runs at the speed of a product.
// So a colour's rows are shared among the threads (static schedule), the colours taken in
// turn with a barrier between them (the end of each `omp for`); every row is computed by
// one thread in the order of one thread, and the sweeps give the same result on any
// number of threads (linalg/parallel.hpp, rule 1).

namespace {

// s − Σ_p T_p x[column_p] and s + Σ_p T_p x[column_p] over row k (in sweep order) of a
// triangle T: a row of a sweep (a solve) and of a product.
template <class Triangle>
double minus_row(const Triangle& T, int k, double s, const double* x) {
  for (int p = T.start[k]; p < T.start[k + 1]; ++p) s -= T.value[p] * x[T.column[p]];
  return s;
}
template <class Triangle>
double plus_row(const Triangle& T, int k, double s, const double* x) {
  for (int p = T.start[k]; p < T.start[k + 1]; ++p) s += T.value[p] * x[T.column[p]];
  return s;
}

}  // namespace

bool SymmetricGaussSeidel::threaded() const { return lower_.column.size() + upper_.column.size() >= kParallelWork; }

// Row k (unknown i) of first_residual(): Σ Ŝ_ij ŷ_j over both triangles and Σ Ŝ_ij u_j over
// the lower one share the lower entries' reads.
void SymmetricGaussSeidel::first_residual_row(int k, const double* b, const double* y_hat, double* u,
                                              double* r_hat, double* r) const {
  const int i = rows_[k];
  double upper_y = 0.0, lower_y = 0.0, lower_u = 0.0;
  for (int p = upper_.start[k]; p < upper_.start[k + 1]; ++p) upper_y += upper_.value[p] * y_hat[upper_.column[p]];
  for (int p = lower_.start[k]; p < lower_.start[k + 1]; ++p) {
    const int j = lower_.column[p];
    lower_y += lower_.value[p] * y_hat[j];
    lower_u += lower_.value[p] * u[j];
  }
  const double g = b[i] / sqrt_diagonal_[i];
  u[i] = (g - upper_y) - lower_u;
  r_hat[i] = u[i] - y_hat[i];
  r[i] = sqrt_diagonal_[i] * (((g - y_hat[i]) - upper_y) - lower_y);
}

void SymmetricGaussSeidel::first_residual(const std::vector<char>& held, const double* b, const double* y_hat,
                                          double* u, double* r_hat, double* r) const {
#pragma omp parallel if (threaded())
  for (int c = 0; c < colours(); ++c) {
#pragma omp for schedule(static)
    for (int k = colour_start_[c]; k < colour_start_[c + 1]; ++k) {
      const int i = rows_[k];
      if (held[i])
        u[i] = r_hat[i] = r[i] = 0.0;
      else
        first_residual_row(k, b, y_hat, u, r_hat, r);
    }
  }
}

void SymmetricGaussSeidel::multiply_lower(const std::vector<char>& held, const double* in, double* out) const {
#pragma omp parallel for schedule(static) if (threaded())
  for (int k = 0; k < size(); ++k) {
    const int i = rows_[k];
    out[i] = held[i] ? 0.0 : plus_row(lower_, k, in[i], in);
  }
}

double SymmetricGaussSeidel::apply(const std::vector<char>& held, const double* v, double* t, double* w,
                                   double* q) const {
  const int n = size();
#pragma omp parallel if (threaded())
  {
    // t = L̂⁻ᵀ v: the colours in reverse, each row gathering later colours
    for (int c = colours() - 1; c >= 0; --c) {
#pragma omp for schedule(static)
      for (int k = colour_start_[c]; k < colour_start_[c + 1]; ++k) {
        const int i = rows_[k];
        t[i] = held[i] ? 0.0 : minus_row(upper_, k, v[i], t);
      }
    }
    // w = L̂⁻¹ (v − t), q = t + w
    for (int c = 0; c < colours(); ++c) {
#pragma omp for schedule(static)
      for (int k = colour_start_[c]; k < colour_start_[c + 1]; ++k) {
        const int i = rows_[k];
        const double s = held[i] ? 0.0 : minus_row(lower_, k, v[i] - t[i], w);
        w[i] = s;
        q[i] = t[i] + s;
      }
    }
  }
  // vᵀq in a separate, vectorized pass by blocks: inside the sweep the sum would chain
  // every row, and its order would follow the colours' split among the threads
  return dot(n, v, q);
}

SymmetricGaussSeidel::FreeRows SymmetricGaussSeidel::free_rows(const std::vector<int>& free) const {
  // (rows_ lists each colour's rows in increasing order, so the free rows, taken in
  // increasing order, come out increasing within each colour)
  FreeRows f;
  f.colour_start.assign(colours() + 1, 0);
  for (int i : free) ++f.colour_start[colour_[i] + 1];
  for (int c = 0; c < colours(); ++c) f.colour_start[c + 1] += f.colour_start[c];
  f.position.resize(free.size());
  std::vector<int> next(f.colour_start.begin(), f.colour_start.end() - 1);
  for (int i : free) f.position[next[colour_[i]]++] = position_[i];
  return f;
}

void SymmetricGaussSeidel::first_residual(const FreeRows& free, const double* b, const double* y_hat, double* u,
                                          double* r_hat, double* r) const {
  const int colours = static_cast<int>(free.colour_start.size()) - 1;
#pragma omp parallel if (threaded())
  for (int c = 0; c < colours; ++c) {
#pragma omp for schedule(static)
    for (int m = free.colour_start[c]; m < free.colour_start[c + 1]; ++m)
      first_residual_row(free.position[m], b, y_hat, u, r_hat, r);
  }
}

void SymmetricGaussSeidel::multiply_lower(const FreeRows& free, const double* in, double* out) const {
  const int m_free = static_cast<int>(free.position.size());
#pragma omp parallel for schedule(static) if (threaded())
  for (int m = 0; m < m_free; ++m) {
    const int k = free.position[m];
    const int i = rows_[k];
    out[i] = plus_row(lower_, k, in[i], in);
  }
}

// The sweeps of apply() over the free rows: the held rows' t and w, which the free rows
// read, are 0 already.
void SymmetricGaussSeidel::apply(const FreeRows& free, const double* v, double* t, double* w, double* q) const {
  const int colours = static_cast<int>(free.colour_start.size()) - 1;
#pragma omp parallel if (threaded())
  {
    for (int c = colours - 1; c >= 0; --c) {
#pragma omp for schedule(static)
      for (int m = free.colour_start[c]; m < free.colour_start[c + 1]; ++m) {
        const int k = free.position[m];
        const int i = rows_[k];
        t[i] = minus_row(upper_, k, v[i], t);
      }
    }
    for (int c = 0; c < colours; ++c) {
#pragma omp for schedule(static)
      for (int m = free.colour_start[c]; m < free.colour_start[c + 1]; ++m) {
        const int k = free.position[m];
        const int i = rows_[k];
        const double s = minus_row(lower_, k, v[i] - t[i], w);
        w[i] = s;
        q[i] = t[i] + s;
      }
    }
  }
}

}  // namespace cdyn
