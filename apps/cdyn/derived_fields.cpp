// derived_fields.cpp — σ, ε, von Mises, contact pressure and regions as VTU arrays.
#include "derived_fields.hpp"

#include <algorithm>

#include "cdyn/post/contact_force.hpp"
#include "cdyn/post/stress.hpp"

namespace cdyn::app {

namespace {

// A symmetric tensor as the 9 components of a 3 × 3 tensor, row by row
// (xx xy xz / yx yy yz / zx zy zz), the layout ParaView reads as a tensor.
void append_tensor(std::vector<double>& to, const SymmetricTensor& t) {
  to.insert(to.end(), {t.xx, t.xy, t.xz, t.xy, t.yy, t.yz, t.xz, t.yz, t.zz});
}

// sigma, epsilon (9 components) and von_mises (1) of a list of stress states.
std::vector<FieldArray> stress_arrays(const std::vector<StressState>& states) {
  FieldArray sigma{"sigma", 9, {}}, epsilon{"epsilon", 9, {}}, vm{"von_mises", 1, {}};
  for (const StressState& s : states) {
    append_tensor(sigma.values, s.sigma);
    append_tensor(epsilon.values, s.epsilon);
    vm.values.push_back(s.von_mises);
  }
  return {std::move(sigma), std::move(epsilon), std::move(vm)};
}

// The cell states of "sigma" and "epsilon" arrays (9 components, row by row).
std::vector<StressState> stress_states(const FieldArray& sigma, const FieldArray& epsilon) {
  auto tensor = [](const double* a) { return SymmetricTensor{a[0], a[4], a[8], a[1], a[2], a[5]}; };
  std::vector<StressState> out(sigma.values.size() / 9);
  for (std::size_t c = 0; c < out.size(); ++c) {
    out[c].sigma = tensor(&sigma.values[9 * c]);
    out[c].epsilon = tensor(&epsilon.values[9 * c]);
  }
  return out;
}

const FieldArray& named(const std::vector<FieldArray>& arrays, const std::string& name) {
  return *std::find_if(arrays.begin(), arrays.end(), [&](const FieldArray& a) { return a.name == name; });
}

}  // namespace

DerivedFields::DerivedFields(const Simulation& sim)
    : sim_(sim), friction_(sim.with_friction) {
  if (sim.components > 1 && sim.has_obstacle) {
    contact_.emplace(sim.problem);
    weight_ = whole_contact_weights(sim, *contact_);
  }
}

void DerivedFields::add_vertex_stress(const Mesh& whole, ExtraFields& gathered) const {
  if (sim_.components == 1 || !sim_.spec.output.stress) return;
  const std::vector<StressState> cells = stress_states(named(gathered.cell, "sigma"), named(gathered.cell, "epsilon"));
  std::vector<FieldArray> vertex = stress_arrays(vertex_stress(whole, cells));
  gathered.point.insert(gathered.point.begin() + 3, vertex.begin(), vertex.end());
}

ExtraFields DerivedFields::operator()(const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy,
                                     const State* state) const {
  ExtraFields out;
  const Mesh& mesh = *sim_.mesh;
  if (sim_.components > 1 && sim_.spec.output.stress) {
    const std::vector<StressState> cells =
        cell_stress(*sim_.problem.W, U_full, sim_.materials.lambda, sim_.materials.mu);
    out.cell = stress_arrays(cells);
    if (!sim_.partition) out.point = stress_arrays(vertex_stress(mesh, cells));
  }
  if (contact_) {
    FieldArray pressure{"contact_pressure", 1, std::vector<double>(mesh.n_vertices(), 0.0)};
    const std::vector<ContactPressure::Vertex>& vertices = contact_->vertices();
    if (reaction_xy.size() > 0)
      for (std::size_t i = 0; i < vertices.size(); ++i)
        pressure.values[vertices[i].vertex] =
            weight_[i] > 0.0 ? contact_->normal_force(reaction_xy, vertices[i]) / weight_[i] : 0.0;
    out.point.push_back(std::move(pressure));
  }
  const ConstrainedProblem& p = sim_.problem;
  if (friction_) {
    // in the plane λ_T and the slip along t (signed); in space their vectors in x, y, z
    const int d = mesh.dim == 3 ? 3 : 1;
    FieldArray force{"tangential_force", d, std::vector<double>(d * mesh.n_vertices(), 0.0)};
    FieldArray slip{"slip", d, std::vector<double>(d * mesh.n_vertices(), 0.0)};
    FieldArray status{"contact_status", 1, std::vector<double>(mesh.n_vertices(), -1.0)};
    const bool stepped = state && state->slip.size() > 0;  // (not before the first step)
    const Eigen::VectorXd force_xy = stepped && d == 3 ? tangential_xy(p, state->reaction) : Eigen::VectorXd();
    const Eigen::VectorXd slip_xy = stepped && d == 3 ? tangential_xy(p, state->slip) : Eigen::VectorXd();
    for (std::size_t k = 0; k < p.friction.size(); ++k) {
      const int v = p.contact_nodes[p.friction[k].node].vertex;
      status.values[v] = 0.0;
      if (!stepped) continue;
      status.values[v] = state->contact_status[k];
      if (d == 1) {
        force.values[v] = tangential_magnitude(p.friction[k], state->reaction);
        slip.values[v] = tangential_magnitude(p.friction[k], state->slip);
        continue;
      }
      const Point F = vertex_force(p, force_xy, v), D = vertex_force(p, slip_xy, v);
      const double f[3] = {F.x, F.y, F.z}, s[3] = {D.x, D.y, D.z};
      std::copy(f, f + 3, force.values.begin() + 3 * v);
      std::copy(s, s + 3, slip.values.begin() + 3 * v);
    }
    for (FieldArray* a : {&force, &slip, &status}) out.point.push_back(std::move(*a));
  }
  if (sim_.components > 1 && !mesh.cell_region.empty())
    out.cell.push_back({"region", 1, std::vector<double>(mesh.cell_region.begin(), mesh.cell_region.end())});
  return out;
}

}  // namespace cdyn::app
