// problems/elastic_contact.cpp — assembling the plane-strain Signorini problem on the free dofs
// (see problems/elastic_contact.hpp for the equations and the contact convention).
#include "cdyn/problems/elastic_contact.hpp"

#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/rotated.hpp"
#include "cdyn/problems/nodal_rotation.hpp"

namespace cdyn {

namespace {

Point unit(const Point& n) {
  const double norm = std::hypot(n.x, n.y);
  if (!(norm > 0.0) || !std::isfinite(norm)) throw InputError("normal", "must be a nonzero finite vector");
  return {n.x / norm, n.y / norm};
}

// `where` is "" for the body's material, else " (region 'name')".
void check_material(const Material& m, const std::string& where) {
  if (!(m.rho > 0.0) || !std::isfinite(m.rho)) throw InputError("rho", "must be positive" + where);
  if (!(m.mu > 0.0) || !std::isfinite(m.mu)) throw InputError("mu", "the shear modulus must be positive" + where);
  if (!(m.lambda + m.mu > 0.0) || !std::isfinite(m.lambda))
    throw InputError("lambda", "plane strain needs λ + μ > 0 (got λ = " + std::to_string(m.lambda) + ")" + where);
}

// The constraint n·u(a) ≥ g(a) at the contact vertices, written as bounds on the
// problem's unknowns (rotating the nodes that need it), and the contact dofs that
// the redistributed mass makes massless.
struct ContactSet {
  NodalRotation rotation;           // nodes whose unknowns become (n·u, t·u)
  std::vector<int> bound_index;     // free dof carrying each bound
  std::vector<double> bound_value;  // its value
  std::vector<bool> bound_is_lower; // lower (else upper) bound
  std::vector<int> contact_dofs;    // both free components of every contact vertex
};

ContactSet contact_set(const Mesh& mesh, const FESpace& W, const DirichletLift& bc, const Eigen::VectorXd& UD,
                       const ElasticContactData& d) {
  const Point n = unit(d.obstacle_normal);
  const double nk[2] = {n.x, n.y};
  const bool axis_aligned = n.x == 0.0 || n.y == 0.0;
  ContactSet s;
  auto bound = [&s](int i, double value, bool lower) {
    s.bound_index.push_back(i);
    s.bound_value.push_back(value);
    s.bound_is_lower.push_back(lower);
  };
  for (int v : mesh.part_vertices(d.contact_parts)) {
    const int i[2] = {bc.free_index(W.vertex_dof(v, 0)), bc.free_index(W.vertex_dof(v, 1))};
    for (int k : {0, 1})
      if (i[k] >= 0) s.contact_dofs.push_back(i[k]);
    const double g = obstacle_gap(d, mesh.vertices[v]);
    if (i[0] >= 0 && i[1] >= 0) {
      if (!axis_aligned || d.rotate_always) {
        // Unknown i[0] becomes n·u (and i[1] t·u): n·u ≥ g is a lower bound on it.
        s.rotation.nodes.push_back({i[0], i[1], n.x, n.y});
        bound(i[0], g, true);
      } else {
        // n = ±e_k: ±u_k ≥ g.
        const int k = n.x != 0.0 ? 0 : 1;
        bound(i[k], nk[k] > 0 ? g : -g, nk[k] > 0);
      }
    } else if (i[0] >= 0 || i[1] >= 0) {
      // A roller: u_j = u_D,j is data, n_k u_k ≥ g − n_j u_D,j bounds the free u_k.
      const int k = i[0] >= 0 ? 0 : 1, j = 1 - k;
      if (nk[k] == 0.0) continue;  // the constraint does not involve the free unknown
      const double value = (g - nk[j] * UD[W.vertex_dof(v, j)]) / nk[k];
      bound(i[k], value, nk[k] > 0);
    }
    // Both components fixed: a Dirichlet vertex is not constrained.
  }
  return s;
}

}  // namespace

Lame lame_parameters(double E, double nu) {
  if (!(E > 0.0) || !std::isfinite(E)) throw InputError("E", "Young's modulus must be positive");
  if (!(nu > -1.0 && nu < 0.5)) throw InputError("nu", "Poisson's ratio must lie in (−1, ½)");
  return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
}

CellMaterials cell_materials(const Mesh& mesh, const ElasticContactData& d) {
  const Material body{d.rho, d.lambda, d.mu};
  check_material(body, "");
  if (d.region_materials.empty()) return {d.rho, d.lambda, d.mu};
  const int n_regions = static_cast<int>(mesh.region_names.size());
  std::vector<const Material*> of_region(n_regions, nullptr);
  for (const auto& [r, m] : d.region_materials) {
    if (r < 0 || r >= n_regions || mesh.cell_region.empty())
      throw InputError("regions", "region " + std::to_string(r) + " is not a region of the mesh (it has " +
                                      std::to_string(n_regions) + ")");
    if (of_region[r]) throw InputError("regions", "region '" + mesh.region_names[r] + "' is given two materials");
    check_material(m, " (region '" + mesh.region_names[r] + "')");
    of_region[r] = &m;
  }
  std::vector<double> rho(mesh.n_cells()), lambda(mesh.n_cells()), mu(mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const int r = mesh.cell_region[c];
    const Material& m = r >= 0 && of_region[r] ? *of_region[r] : body;
    rho[c] = m.rho;
    lambda[c] = m.lambda;
    mu[c] = m.mu;
  }
  return {CellCoefficient(std::move(rho)), CellCoefficient(std::move(lambda)), CellCoefficient(std::move(mu))};
}

double obstacle_gap(const ElasticContactData& d, const Point& a) {
  const Point n = unit(d.obstacle_normal);
  return -((a.x - d.obstacle_point.x) * n.x + (a.y - d.obstacle_point.y) * n.y);
}

ConstrainedProblem build_elastic_contact(const Mesh& mesh, const ElasticContactData& d) {
  if (mesh.dim != 2) throw InputError("mesh", "plane-strain elasticity needs a 2D mesh");
  const CellMaterials material = cell_materials(mesh, d);
  if (d.obstacle && d.contact_parts.empty()) throw InputError("contact", "elasticity with an obstacle needs a contact part Γ_C");
  ConstrainedProblem p;
  p.W = std::make_unique<FESpace>(mesh, d.mass.W, 2);
  const FESpace& W = *p.W;
  p.bc = std::make_unique<DirichletLift>(W, d.dirichlet_parts, d.dirichlet_components);
  p.A_full = assemble_elasticity(W, material.lambda, material.mu);

  // L(t) = ∫_Ω (f + ρ g)·φ_i + ∫_{Γ_N} g_N·φ_i.  One density: ρ g is added to f at the
  // quadrature points; several: ∫ ρ g·φ_i is a load of its own, weighted cell by cell.
  std::vector<Field> f(d.f.begin(), d.f.end());
  const std::vector<Field> gN(d.traction.begin(), d.traction.end());
  const std::vector<int> neumann = d.neumann_parts;
  const std::array<double, 2> g = d.gravity;
  const CellCoefficient rho = material.rho;
  if (rho.is_uniform())
    for (int k : {0, 1})
      f[k] = [fk = f[k], rho_g = rho.value() * g[k]](const Point& x, double t) { return fk(x, t) + rho_g; };
  const bool weighted_gravity = !rho.is_uniform() && (g[0] != 0.0 || g[1] != 0.0);
  p.L_full = [&W, f, gN, neumann, g, rho, weighted_gravity](double t) {
    Eigen::VectorXd L = assemble_load(W, f, t);
    if (weighted_gravity) {
      const std::vector<Field> gk{[g0 = g[0]](const Point&, double) { return g0; },
                                  [g1 = g[1]](const Point&, double) { return g1; }};
      L += assemble_load(W, rho, gk, t);
    }
    if (!neumann.empty()) L += assemble_boundary_load(W, neumann, gN, t);
    return L;
  };
  p.load_is_constant = d.load_is_constant;
  p.UD = d.dirichlet_parts.empty()
             ? Eigen::VectorXd::Zero(W.n_dofs())
             : p.bc->lifting(W, std::vector<Field>(d.dirichlet_value.begin(), d.dirichlet_value.end()));
  const SparseMatrix A_ff = p.bc->restrict(p.A_full);

  // K̄^h.  The contact set (and the rotation) is built even when the obstacle is
  // disabled: the redistributed mass depends on it, and the unconstrained run must
  // keep the same M and the same unknowns.
  const ContactSet contact = contact_set(mesh, W, *p.bc, p.UD, d);
  const double inf = std::numeric_limits<double>::infinity();
  p.lower = Eigen::VectorXd::Constant(A_ff.rows(), -inf);
  p.upper = Eigen::VectorXd::Constant(A_ff.rows(), inf);
  if (d.obstacle)
    for (std::size_t b = 0; b < contact.bound_index.size(); ++b) {
      const int i = contact.bound_index[b];
      (contact.bound_is_lower[b] ? p.lower : p.upper)[i] = contact.bound_value[b];
      p.constrained.push_back(i);
    }

  // Redistributed mass: both components of each contact node are massless, so every
  // normal N_i is in Ker M whatever its direction (mass/mass_model.hpp).
  std::unique_ptr<MassModel> mass = make_mass_model(W, *p.bc, d.mass, material.rho, contact.contact_dofs);

  if (contact.rotation.nodes.empty()) {
    p.A = A_ff;
    p.mass = std::move(mass);
  } else {
    // U_f = R U': A' = Rᵀ A_ff R (symmetrized: the products round differently on the
    // two triangles), M' = Rᵀ M R through the wrapped model.
    SparseMatrix R = rotation_matrix(contact.rotation, static_cast<int>(A_ff.rows()));
    const SparseMatrix Ar = SparseMatrix(R.transpose()) * (A_ff * R);
    p.A = 0.5 * (Ar + SparseMatrix(Ar.transpose()));
    p.A.makeCompressed();
    p.mass = make_rotated_mass_model(std::move(mass), R);
    p.R = std::move(R);
  }
  return p;
}

}  // namespace cdyn
