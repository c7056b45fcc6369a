// supernodal_solve.cpp — the forward and back sweeps of a supernodal factor, by subtrees
// of its elimination tree (the cut and why it gives the same bits: the header).
#include "cdyn/linalg/supernodal_solve.hpp"

#include <algorithm>
#include <queue>
#include <utility>

#include "cdyn/linalg/prefetch.hpp"

namespace cdyn {

namespace {

// Below this many entries of L a solve stays one sweep on one thread: the two parallel
// regions cost microseconds, a sweep of 10⁵ entries about 0.1 ms.
constexpr double kCutWork = 1e5;

// Σ a_r b_r over r < m in a fixed order (four running sums, then their sum): the same
// bits on every call, vectorizable.
double dot(const double* a, const double* b, int m) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int r = 0;
  for (; r + 4 <= m; r += 4) {
    s0 += a[r] * b[r];
    s1 += a[r + 1] * b[r + 1];
    s2 += a[r + 2] * b[r + 2];
    s3 += a[r + 3] * b[r + 3];
  }
  for (; r < m; ++r) s0 += a[r] * b[r];
  return (s0 + s1) + (s2 + s3);
}

// Both sweeps ask for L's columns ahead of their reads (linalg/prefetch.hpp): eight
// columns ahead forward, four back.  Out of cache that took 10 % off the free step at
// n = 640; farther, or also in the supernodes of fewer than four columns, was no better.

// One supernode's block: nc columns, ld rows (its own nc first), values column-major.
struct Block {
  const double* v;
  const int* rows;
  int nc, ld;
  Block(const SupernodalFactor& L, int j)
      : v(L.x + L.px[j]), rows(L.s + L.pi[j]), nc(L.super[j + 1] - L.super[j]), ld(L.pi[j + 1] - L.pi[j]) {}
};

// A supernode at least this wide is a separator of a 3D mesh's kind (see suits()).
constexpr int kWide = 32;

// Forward, one supernode: its diagonal block solved for its unknowns, then E_r = Σ_c L(row, c) x_c
// for the rows below (E: ld − nc entries), to be subtracted from x_row.  The columns are
// taken four at a time, each read once from its top to its bottom: the block's unknowns
// below the four and E are updated by the four in column order, as four passes would
// (the same bits), but each entry loaded and stored once instead of four times — a pass
// per column made the sweep bound by those loads and stores, not by L's entries.
void forward_supernode(const Block& b, double* xs, double* E) {
  const int m = b.ld - b.nc;
  const long ld = b.ld;
  std::fill(E, E + m, 0.0);
  int c = 0;
  for (; c + 4 <= b.nc; c += 4) {
    const double* c0 = b.v + c * ld;
    const double *c1 = c0 + ld, *c2 = c1 + ld, *c3 = c2 + ld;
    prefetch_lines(c0, 8 * ld, 4 * ld);  // the group after next (linalg/prefetch.hpp)
    const double x0 = xs[c] / c0[c];  // (the 4 × 4 diagonal block, a column at a time)
    xs[c] = x0;
    xs[c + 1] -= c0[c + 1] * x0;
    xs[c + 2] -= c0[c + 2] * x0;
    xs[c + 3] -= c0[c + 3] * x0;
    const double x1 = xs[c + 1] / c1[c + 1];
    xs[c + 1] = x1;
    xs[c + 2] -= c1[c + 2] * x1;
    xs[c + 3] -= c1[c + 3] * x1;
    const double x2 = xs[c + 2] / c2[c + 2];
    xs[c + 2] = x2;
    xs[c + 3] -= c2[c + 3] * x2;
    const double x3 = xs[c + 3] / c3[c + 3];
    xs[c + 3] = x3;
    for (int r = c + 4; r < b.nc; ++r) {
      double v = xs[r];
      v -= c0[r] * x0;
      v -= c1[r] * x1;
      v -= c2[r] * x2;
      v -= c3[r] * x3;
      xs[r] = v;
    }
    for (int r = 0; r < m; ++r) {
      const int k = b.nc + r;
      double e = E[r];
      e += c0[k] * x0;
      e += c1[k] * x1;
      e += c2[k] * x2;
      e += c3[k] * x3;
      E[r] = e;
    }
  }
  for (; c < b.nc; ++c) {
    const double* col = b.v + c * ld;
    const double xc = xs[c] / col[c];
    xs[c] = xc;
    for (int r = c + 1; r < b.nc; ++r) xs[r] -= col[r] * xc;
    for (int r = 0; r < m; ++r) E[r] += col[b.nc + r] * xc;
  }
}

// x_row −= E for the block's rows lo … hi − 1 (E's entries from row position lo).
void subtract(const Block& b, const double* E, int lo, int hi, double* x) {
  for (int r = lo; r < hi; ++r) x[b.rows[r]] -= E[r - lo];
}

// Back: the supernode's unknowns from its ancestors' (all final), Lᵀ's rows being L's
// columns (G: a workspace of ld − nc entries).
void back_supernode(const Block& b, double* x, double* G) {
  double* xs = x + b.rows[0];
  const int m = b.ld - b.nc;
  for (int r = 0; r < m; ++r) G[r] = x[b.rows[b.nc + r]];
  for (int c = b.nc - 1; c >= 0; --c) {
    const double* col = b.v + static_cast<long>(c) * b.ld;
    prefetch_lines(col, -4L * b.ld, b.ld);  // four columns back: this supernode's or the one before
    double t = xs[c] - dot(col + b.nc, G, m);
    for (int r = c + 1; r < b.nc; ++r) t -= col[r] * xs[r];
    xs[c] = t / col[c];
  }
}

}  // namespace

bool SupernodalSolve::suits(const SupernodalFactor& L) {
  double wide = 0.0, total = 0.0;
  for (int j = 0; j < L.nsuper; ++j) {
    const Block b(L, j);
    const double entries = static_cast<double>(b.ld) * b.nc;
    total += entries;
    if (b.nc >= kWide) wide += entries;
  }
  return wide <= 0.5 * total;
}

SupernodalSolve::SupernodalSolve(const SupernodalFactor& L, int threads) : threads_(threads) {
  const int ns = L.nsuper;
  tail_.assign(ns, 0);
  tail_start_.assign(ns, 0);
  in_tree_.assign(ns, 0);
  std::vector<int> of_column(L.n);
  std::vector<double> work(ns);
  double total = 0.0;
  for (int j = 0; j < ns; ++j) {
    const Block b(L, j);
    for (int k = L.super[j]; k < L.super[j + 1]; ++k) of_column[k] = j;
    max_rows_ = std::max(max_rows_, b.ld);
    // (the entries, and per row and supernode the gathers, scatters and loop starts)
    work[j] = static_cast<double>(b.ld) * b.nc + 4.0 * b.ld + 16.0;
    total += work[j];
  }
  if (threads <= 1 || total < kCutWork) return;
  // The supernodal tree: a supernode's parent holds its first row below its own columns.
  // CHOLMOD postorders the tree, so a subtree is a contiguous range ending at its root.
  std::vector<int> parent(ns, -1), first(ns), size(ns, 1);
  std::vector<double> subtree(work);
  std::vector<std::vector<int>> children(ns);
  for (int j = 0; j < ns; ++j) first[j] = j;
  for (int j = 0; j < ns; ++j) {
    const Block b(L, j);
    if (b.ld == b.nc) continue;
    const int p = of_column[b.rows[b.nc]];
    if (p <= j) return;  // not postordered: one sweep
    parent[j] = p;
    children[p].push_back(j);
    subtree[p] += subtree[j];
    first[p] = std::min(first[p], first[j]);
    size[p] += size[j];
  }
  for (int j = 0; j < ns; ++j)
    if (size[j] != j - first[j] + 1) return;  // a subtree not contiguous: one sweep
  // Split the largest subtree into its children (its root joins R), again and again, and
  // keep the cut whose sweep is estimated fastest: R's work, one thread's, plus the most
  // loaded thread's, the subtrees dealt out largest first to the least loaded thread.
  // Splitting lowers the largest load (better balance) and raises R's work; a 2D mesh's
  // top separators are small, so the best cut leaves few of them in R.
  using Item = std::pair<double, int>;
  const auto roots = [&] {
    std::priority_queue<Item> open;
    for (int j = 0; j < ns; ++j)
      if (parent[j] < 0) open.push({subtree[j], j});
    return open;
  };
  const auto split = [&](std::priority_queue<Item>& open) {
    const int j = open.top().second;
    open.pop();
    for (int c : children[j]) open.push({subtree[c], c});
    return work[j];
  };
  const auto makespan = [&](std::priority_queue<Item> open) {  // (a copy: popped largest first)
    std::vector<double> load(threads, 0.0);
    for (; !open.empty(); open.pop()) *std::min_element(load.begin(), load.end()) += open.top().first;
    return *std::max_element(load.begin(), load.end());
  };
  int best_splits = 0;
  {
    std::priority_queue<Item> open = roots();
    double in_r = 0.0, best = makespan(open);
    // (past a grain of 1/16 of a thread's share, or 64 subtrees a thread, more splits
    // cannot balance much better and only feed R)
    const double grain = total / (16.0 * threads);
    for (int splits = 1; !open.empty() && open.top().first > grain && open.size() < 64u * threads; ++splits) {
      in_r += split(open);
      const double t = in_r + makespan(open);
      if (t < best) best = t, best_splits = splits;
    }
  }
  std::priority_queue<Item> open = roots();
  for (int k = 0; k < best_splits; ++k) split(open);
  std::vector<Item> trees;
  for (; !open.empty(); open.pop()) trees.push_back(open.top());  // largest first
  std::vector<double> load(threads, 0.0);
  groups_.assign(threads, {});
  double in_trees = 0.0;
  for (const Item& t : trees) {
    const int g = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    load[g] += t.first;
    in_trees += t.first;
    const int root = t.second;
    groups_[g].push_back({first[root], root});
    const int last_column = L.super[root + 1] - 1;
    for (int j = first[root]; j <= root; ++j) {
      in_tree_[j] = 1;
      const Block b(L, j);
      int p = b.nc;
      while (p < b.ld && b.rows[p] <= last_column) ++p;
      // The split assumes the rows sorted (CHOLMOD sorts them): a row of the subtree
      // after the split would be updated after its own solve.  Else one sweep.
      for (int q = p; q < b.ld; ++q)
        if (b.rows[q] <= last_column) {
          groups_.clear();
          in_tree_.assign(ns, 0);
          tail_entries_ = 0;
          return;
        }
      tail_[j] = p;
      tail_start_[j] = tail_entries_;
      tail_entries_ += b.ld - p;
    }
  }
  for (auto& g : groups_) std::sort(g.begin(), g.end(), [](Range a, Range b) { return a.first < b.first; });
  serial_fraction_ = 1.0 - in_trees / total;
  span_fraction_ = serial_fraction_ + *std::max_element(load.begin(), load.end()) / total;
}

void SupernodalSolve::solve(const SupernodalFactor& L, double* x) const {
  forward(L, x);
  backward(L, x);
}

void SupernodalSolve::forward(const SupernodalFactor& L, double* x) const {
  const int ns = L.nsuper;
  const int groups = static_cast<int>(groups_.size());
  std::vector<double> E(max_rows_);
  tails_.resize(tail_entries_);
  double* tails = tails_.data();
  // Forward: the subtrees, each by one thread, their updates to their own rows made and
  // those to R's rows computed (subtracted in order below).
#pragma omp parallel for schedule(static, 1) num_threads(std::max(groups, 1)) if (groups > 1)
  for (int g = 0; g < groups; ++g) {
    std::vector<double> work(max_rows_);
    for (const Range& range : groups_[g])
      for (int j = range.first; j <= range.last; ++j) {
        const Block b(L, j);
        forward_supernode(b, x + b.rows[0], work.data());
        subtract(b, work.data(), b.nc, tail_[j], x);
        std::copy(work.data() + (tail_[j] - b.nc), work.data() + (b.ld - b.nc), tails + tail_start_[j]);
      }
  }
  // Then every supernode in order: R's solved, the subtrees' updates to R subtracted.
  for (int j = 0; j < ns; ++j) {
    const Block b(L, j);
    if (in_tree_[j]) {
      subtract(b, tails + tail_start_[j], tail_[j], b.ld, x);
    } else {
      forward_supernode(b, x + b.rows[0], E.data());
      subtract(b, E.data(), b.nc, b.ld, x);
    }
  }
}

void SupernodalSolve::backward(const SupernodalFactor& L, double* x) const {
  const int ns = L.nsuper;
  const int groups = static_cast<int>(groups_.size());
  std::vector<double> G(max_rows_);
  // R from the root down, then the subtrees, each by one thread.
  for (int j = ns - 1; j >= 0; --j)
    if (!in_tree_[j]) back_supernode(Block(L, j), x, G.data());
#pragma omp parallel for schedule(static, 1) num_threads(std::max(groups, 1)) if (groups > 1)
  for (int g = 0; g < groups; ++g) {
    std::vector<double> work(max_rows_);
    for (const Range& range : groups_[g])
      for (int j = range.last; j >= range.first; --j) back_supernode(Block(L, j), x, work.data());
  }
}

SupernodalPaths::SupernodalPaths(const SupernodalFactor& L) : of_column_(L.n), parent_(L.nsuper, -1), z_(L.n, 0.0) {
  int max_rows = 0;
  for (int j = 0; j < L.nsuper; ++j) {
    for (int k = L.super[j]; k < L.super[j + 1]; ++k) of_column_[k] = j;
    max_rows = std::max(max_rows, L.pi[j + 1] - L.pi[j]);
  }
  for (int j = 0; j < L.nsuper; ++j) {
    const Block b(L, j);
    if (b.ld > b.nc) parent_[j] = of_column_[b.rows[b.nc]];
  }
  E_.resize(max_rows);
}

double SupernodalPaths::unit_forward(const SupernodalFactor& L, int k, std::vector<int>& rows,
                                     std::vector<double>& values) const {
  rows.clear();
  values.clear();
  double flops = 0.0;
  z_[k] = 1.0;
  // (the entries of k's supernode before k are zero and stay so)
  for (int j = of_column_[k]; j >= 0; j = parent_[j]) {
    const Block b(L, j);
    forward_supernode(b, z_.data() + b.rows[0], E_.data());
    subtract(b, E_.data(), b.nc, b.ld, z_.data());
    flops += 2.0 * b.ld * b.nc;
    for (int c = std::max(k, L.super[j]); c < L.super[j + 1]; ++c) {
      rows.push_back(c);
      values.push_back(z_[c]);
      z_[c] = 0.0;
    }
  }
  return flops;
}

}  // namespace cdyn
