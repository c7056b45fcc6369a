// contact_history.hpp — what an elasticity run reports about its contact with the rigid
// plane (docs/outputs.md): the normal contact force and pressure at every constrained
// vertex of Γ_C (contact.csv), the total contact force and the linear momentum of each
// step (history.csv), and the impact summary of summary.json.
//
// The force on a constrained vertex a is the step's reaction Gᵀλ brought back to (x, y)
// components (ConstrainedProblem::global); its normal part
//
//     F_N(a) = F(a)·n = −λ_N(a) ≥ 0          (the seed's λ_N ≤ 0, elastic_contact.hpp)
//
// is a nodal force, the weak form's integral of the contact pressure against the
// vertex's hat function.  The pressure is F_N(a) / w(a), w(a) = ∫_{Γ_C} φ_a ds the
// vertex's share of Γ_C (half the length of its contact edges: the P1 hat function on
// the boundary, whatever W^h is, since the constraint is nodal at the vertices), so
// that Σ_a F_N(a) = Σ_a p(a) w(a) is the total contact force.
//
// Linear momentum of the free motion: P_k = Σ_i (Bᵀ V)_i T_k,i with T_k the
// interpolated translation e_k (in W^h for P1, P1+ and P2: its bubble and edge
// coefficients are those of a constant), i.e. ∫ ρ v_h·e_k of the velocity field (the
// classical models: Σ (M U̇)_i T_k,i).  Dirichlet dofs are left out: a clamped body's
// momentum is not conserved anyway.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "cdyn/atomic_file.hpp"
#include "simulation.hpp"

namespace cdyn::app {

// The (x, y) force on a vertex from a step's reaction in Cartesian free components
// (ConstrainedProblem::global(reaction)); 0 on fixed components.
Point vertex_force(const ConstrainedProblem& p, const Eigen::VectorXd& reaction_xy, int vertex);

// The seed's λ_N = −F·n at a constrained vertex, 0 elsewhere (the probes' lambda@P).
double normal_multiplier(const Simulation& sim, const Eigen::VectorXd& reaction_xy, int vertex);

// ∫ ρ v_h of a state's velocity V (see above).
class LinearMomentum {
 public:
  explicit LinearMomentum(const Simulation& sim);
  Point operator()(const Eigen::VectorXd& V) const;

 private:
  const ConstrainedProblem& p_;
  Eigen::VectorXd T_[2];  // the translations e_x, e_y on the free dofs (Cartesian)
};

// contact.csv: one row per constrained vertex of Γ_C at each recorded step.
class ContactHistory {
 public:
  ContactHistory(const Simulation& sim, const std::filesystem::path& file);

  // The total normal contact force Σ F_N(a) of the state (U_full all dofs of W^h,
  // reaction_xy the reaction in Cartesian free components, empty before step 1); writes
  // the rows when `write` is true.
  double record(int step, double t, const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy, bool write);

  // Gives the file its name (it is written under a temporary one until then: a run
  // that dies leaves no contact.csv that looks complete, atomic_file.hpp).
  void close() { file_.commit(); }

 private:
  struct Vertex {
    int vertex;
    double s;       // coordinate along the plane, (a − p)·t, t = (−n_y, n_x)
    double weight;  // w(a) = ∫_{Γ_C} φ_a ds
  };
  const Simulation& sim_;
  std::vector<Vertex> vertices_;  // sorted by s
  AtomicFile file_;
  std::ostream& csv_;
};

// The first impact of the run (summary.json's "impact"): first and last step with an
// active constraint, their times, the contact duration t_last − t_first + dt (the
// contact starts within the first step and ends within the one after the last, so the
// estimate is good to ± dt), the peak total contact force and when, and the energy and
// momentum just before (the step before the first contact) and just after (the first
// step without contact after the last one; null while still in contact at T), and the
// impulse, centroid and width of the force history with their half-sine equivalents.
class ImpactMonitor {
 public:
  struct Snapshot {
    int step = -1;
    double t = 0, E = 0, E_kin = 0;
    Point P;
  };
  void observe(const Snapshot& now, int active, double contact_force);
  nlohmann::ordered_json summary(double dt) const;

 private:
  Snapshot previous_, before_, after_;
  int first_ = -1, last_ = -1, contact_steps_ = 0;
  double t_first_ = 0, t_last_ = 0, peak_ = 0, t_peak_ = 0;
  double force_sum_ = 0, force_tau_ = 0, force_tau2_ = 0;  // Σ F, Σ F τ, Σ F τ², τ = t − t_first
};

}  // namespace cdyn::app
