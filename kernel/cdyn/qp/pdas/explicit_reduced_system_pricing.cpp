// explicit_reduced_system_pricing.cpp — which way ExplicitReducedSystem takes to the next
// active set: CG on S̃, row updates of the factor, a refactorization (of S̃ or of a free
// block), or a resync of the factor to a settled set.  Each way is priced in flops as
// CHOLMOD's analysis and modifications count them and as CG's iterations so far cost,
// never by clocks, so that a run repeats exactly (docs/qp.md, docs/performance.md).
#include "cdyn/qp/pdas/explicit_reduced_system.hpp"

#include <algorithm>
#include <cmath>

namespace cdyn {

// Row updates beyond this many changes cost more than a factorization: measured on the
// obstacle (docs/performance.md), one row update costs 1/300 to 1/600 of a
// factorization from 6k to 100k unknowns, and the break-even grows with the size.
int ExplicitReducedSystem::update_limit() const {
  return opt_.pdas_update_limit >= 0 ? opt_.pdas_update_limit : std::max(300, n_ / 100);
}

// Whether a fresh factorization of S̃ costs less than `changes` row updates at their
// mean flops so far: under half their flops (the analysis's count; the margin because a
// refactorization also copies the analysis and rebuilds the supernodes: at n = 80 on the
// membrane without CG, refactorizations chosen at 1.3× fewer flops made the steps 8 %
// slower).  On a small or nearly banded S — the thin beam's 404 unknowns: 1.4e4 flops a
// factorization — it is the cheaper way at any number of changes.
bool ExplicitReducedSystem::refactorization_pays(int changes) const {
  return updates_measured_ > 0 && 2.0 * chol_.factorization_flops() < changes * (update_flops_ / updates_measured_);
}

// Whether bringing the factor (S̃'s, not a free block's) to a set `changes` unknowns away
// is priced as a refactorization rather than as that many row updates: beyond
// update_limit(), where a refactorization pays, and before any row update is measured
// (then a refactorization's count stands in for them).  (sync_factor itself does row
// updates in that last case, to measure them.)  For cg_pays and resync_pays.
bool ExplicitReducedSystem::priced_as_refactorization(int changes) const {
  return changes > update_limit() || updates_measured_ == 0 || refactorization_pays(changes);
}

// Whether the factor should now be brought to `held` although CG would do: when the
// active set has settled — used by the last kSettled calls in a row (while the contact
// zone chatters, each set serves at most two: the last solves of a step and the first of
// the next) — so that the coming steps are one forward/back solve each again; or after
// pdas_cg_resync CG iterations since the last sync, if set.
bool ExplicitReducedSystem::resync_due(const HeldSet& held) const {
  if (opt_.pdas_cg_resync >= 0 && cg_since_sync_ >= opt_.pdas_cg_resync) return true;
  return way_ == Way::Cg && held == cg_held_ && cg_held_call_ != calls_ && cg_mode_uses_ + 1 >= kSettled &&
         resync_pays(held);
}

// Whether bringing the factor to a settled set costs less than the CG it saves: each
// call the set serves from now on costs one solve with the factor instead of a CG pair
// (a loose solve and its tight resumption: twice the mean CG solve), and the settled
// sets seen so far served `uses` such calls on average.  A refactorization of the
// condensed P1+/P0 membrane (n = 160) costs 22 forward/back solves' flops, or 110 CG
// iterations; a chattering contact zone that settles for two or three steps at a time
// spent 3.7 ms a step on them: 1.78 times the linear step, 1.42 with this rule
// (docs/performance.md, "Contact in every regime").  Until a settled set has
// ended, and for resting contact (a small free block, cheap to factorize and to solve
// with), it pays.  Flop counts, not clocks: a run repeats exactly.
bool ExplicitReducedSystem::resync_pays(const HeldSet& held) const {
  if (settled_runs_ == 0 || counters_.cg_solves == 0) return true;
  const double uses = settled_uses_ / settled_runs_;
  const Sync sync = sync_cost(held);
  return uses * (cg_pair_flops() - sync.solve_flops) > sync.flops;
}

// What sync_factor(held) will do, in flops, and the flops of a solve it leaves: row
// updates at their mean cost so far, or a refactorization (priced_as_refactorization) —
// of the free block S_II when it leaves at most pdas_free_block of the unknowns free.
// A new free block's flops are estimated from S's: a fraction f of the unknowns of a
// 2D-like graph, f^1.5 of the factorization (nested dissection's N^1.5) and f of the
// solve.  (Measured where it matters, the resting membrane's reconstruction at n = 640:
// 1.2 % of the unknowns free, a block factorization 57 ms against CG's 63 ms a solve,
// where S's whole factorization costs 1.8 s.)
ExplicitReducedSystem::Sync ExplicitReducedSystem::sync_cost(const HeldSet& held) const {
  int changes = 0, n_free = 0;
  for (int i = 0; i < n_; ++i) {
    changes += held[i] != factor_held_[i];
    n_free += !held[i];
  }
  const bool block = factorizes_free_block(n_free);
  if (block_mode_ && block)  // (before any row update on a block is measured, priced as a new block)
    return {block_.updates_measured() && block_.updates_pay(factor_held_, held, update_limit())
                ? changes * block_.update_flops()
                : block_.factorization_flops(),
            block_.solve_flops()};
  // From a free block, a set that leaves more unknowns free (the resting body lifts off)
  // is never row updates of S̃'s factor but its refactorization, priced below.  (Priced
  // as the block's own, a few hundred unknowns, such a jump was always synced: the
  // chattering membrane's lift-off made two factorizations of S̃ where CG was cheaper;
  // without them its P1+/P0 step 16.7, 16.2 → 14.8, 14.5 ms over 100 steps, n = 160.)
  if (!block_mode_ && !priced_as_refactorization(changes))
    return {changes * (update_flops_ / updates_measured_), chol_.solve_flops()};
  const double f = double(n_free) / n_;
  return {chol_.factorization_flops() * (block ? std::pow(f, 1.5) : 1.0), chol_.solve_flops() * (block ? f : 1.0)};
}

// Counts the calls in a row that use one held set (resync_pays).
void ExplicitReducedSystem::track_run(const HeldSet& held) {
  if (held != run_held_) {
    if (run_uses_ >= kSettled) {
      ++settled_runs_;
      settled_uses_ += run_uses_ - kSettled + 1;
    }
    run_held_ = held;
    run_uses_ = 1;
  } else if (run_call_ != calls_) {
    ++run_uses_;
  }
  run_call_ = calls_;
}

// A CG iteration's flops: the product with S (read once, Eisenstat's trick: masked_cg.hpp)
// and the five vector updates.
double ExplicitReducedSystem::cg_iteration_flops() const { return 2.0 * double(S_.nonZeros()) + 12.0 * n_; }

// What a held set costs by CG, a loose solve and its tight resumption, at the mean
// iterations of the CG solves so far (at least one).
double ExplicitReducedSystem::cg_pair_flops() const {
  return 2.0 * double(counters_.cg_iterations) / counters_.cg_solves * cg_iteration_flops();
}

// Whether a CG solve is expected to cost less than bringing the factor to `held`.
// Bringing the factor there is what sync_factor does (sync_cost): beyond update_limit()
// changes, or where it pays (refactorization_pays), a refactorization — of the free
// block alone when most unknowns are held — whose flops the analysis counts; otherwise
// one row update per changed unknown, whose cost CHOLMOD counts (modfl, mean over the
// updates done so far on this pattern; before any is measured, a refactorization's
// count stands in for them).  That is weighed against a CG solve of
// (mean iterations so far) × (2 nnz(S) + 12 n) flops: the product with S and the five
// vector updates of an iteration.  All are sparse loops near memory speed, so flops
// compare their times to within a small factor (docs/performance.md (a): at n = 80
// small changes go to row updates, at n = 160 the contact jumps go to CG; on the thin
// beam a factorization costs 1.4e4 flops, a CG iteration 1.6e4, and CG took 20–30
// iterations).  The first new set goes to CG, whose iteration count no guess gets right
// (5 on the membrane at N_X = 40, dt = 0.01; 30 on the beam): a guess of 50 sent the
// membrane to row updates, 25 % slower a step.  Deterministic: flop counts, not clocks,
// so a run repeats exactly.
bool ExplicitReducedSystem::cg_pays(const HeldSet& held) const {
  if (opt_.pdas_cg_always) return true;
  const double iterations = counters_.cg_solves > 0 ? double(counters_.cg_iterations) / counters_.cg_solves : 50.0;
  const double cg_flops = iterations * cg_iteration_flops();
  // CG's own cost is measured first, but with a block factor, whose alternative is its row
  // updates or a new block (of about the same size), priced as it stands.
  if (!block_mode_ && counters_.cg_solves == 0) return true;
  return sync_cost(held).flops > cg_flops;
}

// Whether the capacitance solve with S's own factor serves the unknowns `held` holds (and
// if so, its matrix made for them): the factor must be S's, in chol_ (a copy of the kept
// one would cost a quarter of a solve, and leave the factor of a settled set), and the
// new columns and the capacitance matrix must cost at most twice what the CG pair the
// set would otherwise take costs beyond the capacitance solve's own sweeps (before any
// CG solve is measured, at most one solve): the columns are kept, and a contact zone
// that stays where it is serves its next QPs with them.  On the chattering membrane at
// n = 160 (P1+/P0 midpoint) a CG pair is 15–18 iterations, about 3.5 solves' time
// (0.26 ms an iteration, 1.2 ms a solve), and sets of 12–50 held vertices whose new
// columns cost more than one solve went to it: 12.6 → 11.8 ms a step with this budget
// (docs/performance.md, "Contact in every regime", nineteenth session, where once and
// four times the pair's cost were measured too).  A column's cost is known once one is
// made: the first set makes one to measure it.  Only where a solve costs at least
// pdas_capacitance_from flops: on a small S the capacitance solve's fixed work (the
// held list, the columns' bookkeeping, two half solves and three passes over the
// unknowns) outweighs what it saves, and the factor is cheap to move (measured: the
// disk, 578 unknowns, 47 → 55 µs a QP; the seed's membrane at n = 20, whose first
// small sets it served, sent its later ones to CG: 0.148 → 0.160 ms a step).  Not for a
// scheme's solve to round-off (by_factor_: the factor brought to the set, as before).
bool ExplicitReducedSystem::capacitance_pays(const HeldSet& held) {
  const double solve = chol_.solve_flops();
  if (by_factor_ || !whole_in_chol_ || !chol_.has_halves() || !(solve >= opt_.pdas_capacitance_from)) return false;
  const double budget = counters_.cg_solves > 0 ? std::max(solve, 2.0 * (cg_pair_flops() - solve)) : solve;
  ScopeTimer timer(counters_.capacitance_s);
  const auto first = std::find_if(held.begin(), held.end(), [](char h) { return h != 0; });
  if (first == held.end()) return false;
  if (capacitance_.mean_column_flops() == 0.0) {
    capacitance_.measure(chol_, static_cast<int>(first - held.begin()));
    ++counters_.capacitance_columns;
  }
  // The held list, given up as soon as the matrix alone would cost more than the budget
  // (an impact's thousands of held unknowns cost one pass to the first few dozen).
  const double length = capacitance_.mean_column_length();
  const auto matrix_flops = [&](double h) { return h * h * length + h * h * h / 3.0; };
  std::vector<int> held_list;
  for (int i = static_cast<int>(first - held.begin()); i < n_; ++i)
    if (held[i]) {
      held_list.push_back(i);
      if (matrix_flops(static_cast<double>(held_list.size())) > budget) return false;
    }
  const int missing = capacitance_.missing(held_list);
  if (missing * capacitance_.mean_column_flops() + matrix_flops(static_cast<double>(held_list.size())) > budget)
    return false;
  counters_.capacitance_columns += missing;
  bool ok = false;
  capacitance_.hold(chol_, held_list, ok);
  return ok;
}

}  // namespace cdyn
