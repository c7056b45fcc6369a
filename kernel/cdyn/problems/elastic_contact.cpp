// problems/elastic_contact.cpp — assembling the plane-strain Signorini problem on the free dofs
// (see problems/elastic_contact.hpp for the equations and the contact convention).
#include "cdyn/problems/elastic_contact.hpp"

#include <cmath>
#include <limits>
#include <map>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/assembly.hpp"
#include "cdyn/mass/rotated.hpp"
#include "cdyn/problems/nodal_rotation.hpp"

namespace cdyn {

namespace {

Point unit(const Point& n) {
  // (the two-argument hypot in the plane, bit-compatible with the 2D formulas)
  const double norm = n.z == 0.0 ? std::hypot(n.x, n.y) : std::hypot(n.x, n.y, n.z);
  if (!(norm > 0.0) || !std::isfinite(norm)) throw InputError("normal", "must be a nonzero finite vector");
  return {n.x / norm, n.y / norm, n.z / norm};
}

// `where` is "" for the body's material, else " (region 'name')"; dim the mesh's.
void check_material(const Material& m, const std::string& where, int dim) {
  if (!(m.rho > 0.0) || !std::isfinite(m.rho)) throw InputError("rho", "must be positive" + where);
  if (!(m.mu > 0.0) || !std::isfinite(m.mu)) throw InputError("mu", "the shear modulus must be positive" + where);
  if (!std::isfinite(m.lambda)) throw InputError("lambda", "must be finite" + where);
  if (dim == 3 && !(3.0 * m.lambda + 2.0 * m.mu > 0.0))
    throw InputError("lambda", "elasticity in space needs 3λ + 2μ > 0 (got λ = " + std::to_string(m.lambda) + ")" + where);
  if (dim != 3 && !(m.lambda + m.mu > 0.0))
    throw InputError("lambda", "plane strain needs λ + μ > 0 (got λ = " + std::to_string(m.lambda) + ")" + where);
}

// One bound of K̄^h: unknown `index` ≥ (or ≤) factor·g(a, t) + offset, with
// g(a, t) = −φ(a, t)/|∇φ(a, 0)| the gap of the vertex's obstacle (a roller's fixed
// component moves the offset).
struct Bound {
  int index = -1;
  int node = -1;  // into ContactSet::nodes
  double factor = 1.0, offset = 0.0;
  bool lower = true;
};

// The constraints n(a)·u(a) ≥ g(a, t) at the contact vertices, written as bounds on the
// problem's unknowns (rotating the nodes that need it), and the contact dofs that the
// redistributed mass makes massless.
struct ContactSet {
  NodalRotation rotation;                             // nodes whose unknowns become (n·u, t·u)
  std::vector<Bound> bounds;
  std::vector<ConstrainedProblem::ContactNode> nodes; // every contact vertex
  std::vector<int> contact_dofs;                      // every free component of every contact vertex
  // The rotated vertices with a free tangential direction: the node, its normal unknown
  // and its tangential ones (where friction can act); normal_share = |m| ≤ 1, the part
  // of the unit normal on the free components (1 but on a roller: docs/friction.md).
  struct Frame {
    int node = -1, normal = -1;
    std::vector<int> tangential;
    double normal_share = 1.0;
  };
  std::vector<Frame> frames;
};

double node_gap(const std::vector<RigidObstacle>& obstacles, const Point& a,
                const ConstrainedProblem::ContactNode& c, double t) {
  return -obstacles[c.obstacle].gap(a, t) / c.scale;
}

// The bound of one contact vertex with normal n and free unknowns i[k] ≥ 0 (k < dim):
// m·u_F ≥ g − Σ_fixed n_j u_D,j, m = n on the free components F.
void constrain_vertex(int v, int node, const Point& n, const std::array<int, 3>& i, int dim, const FESpace& W,
                      const Eigen::VectorXd& UD, bool rotate_always, ContactSet& s) {
  const double nk[3] = {n.x, n.y, n.z};
  std::vector<int> free, along;  // free components; those n has a part along
  double offset = 0.0;
  for (int k = 0; k < dim; ++k) {
    if (i[k] < 0) {
      offset += -nk[k] * UD[W.vertex_dof(v, k)];
      continue;
    }
    free.push_back(k);
    if (nk[k] != 0.0) along.push_back(k);
  }
  const bool all_free = static_cast<int>(free.size()) == dim;
  if (along.empty()) return;  // the constraint does not involve a free unknown
  // (a roller in space, two free components, with friction: rotated below, so that its
  // free tangential direction gets a frame)
  const bool roller_frame = rotate_always && dim == 3 && free.size() == 2;
  if (along.size() == 1 && !(all_free && rotate_always) && !roller_frame) {
    // n_k u_k ≥ g − Σ_fixed n_j u_D,j bounds u_k (n = ±e_k when every component is free).
    const int k = along[0];
    if (all_free)
      s.bounds.push_back({i[k], node, nk[k] > 0 ? 1.0 : -1.0, 0.0, nk[k] > 0});
    else
      s.bounds.push_back({i[k], node, 1.0 / nk[k], offset / nk[k], nk[k] > 0});
    return;
  }
  if (all_free) {
    // The unknowns i become (n·u, t·u) or (n·u, t₁·u, t₂·u): n·u ≥ g bounds the first.
    NodalRotation::Node r{i[0], i[1], n.x, n.y};
    if (dim == 3) {
      r.iz = i[2];
      r.nz = n.z;
    }
    s.rotation.nodes.push_back(r);
    s.bounds.push_back({i[0], node, 1.0, 0.0, true});
    s.frames.push_back({node, i[0], dim == 3 ? std::vector<int>{i[1], i[2]} : std::vector<int>{i[1]}});
    return;
  }
  // Two free components of three, n with a part m along them: rotate them to m/|m| and
  // bound (m/|m|)·u_F ≥ (g + offset)/|m|.  The second rotated unknown, along
  // (−m_b, m_a)/|m|, is tangent to the obstacle (n·t = 0): friction acts there, against
  // the normal force λ_N = (reaction on the first)/|m|.
  const int a = free[0], b = free[1];
  const double m = std::hypot(nk[a], nk[b]);
  s.rotation.nodes.push_back({i[a], i[b], nk[a] / m, nk[b] / m});
  s.bounds.push_back({i[a], node, 1.0 / m, offset / m, true});
  if (roller_frame) s.frames.push_back({node, i[a], {i[b]}, m});
}

ContactSet contact_set(const Mesh& mesh, const FESpace& W, const DirichletLift& bc, const Eigen::VectorXd& UD,
                       const std::vector<RigidObstacle>& obstacles, bool rotate_always) {
  // Each contact vertex goes to the obstacle it is nearest to at t = 0.
  const double h = 1e-6 * mesh.h_max();
  std::map<int, ConstrainedProblem::ContactNode> node_of;
  for (int k = 0; k < static_cast<int>(obstacles.size()); ++k)
    for (int v : mesh.part_vertices(obstacles[k].contact_parts)) {
      const ObstacleNormal n = obstacle_normal(obstacles[k], mesh.vertices[v], h, mesh.dim);
      const ConstrainedProblem::ContactNode c{v, k, n.n, n.scale};
      const auto it = node_of.find(v);
      if (it == node_of.end() || node_gap(obstacles, mesh.vertices[v], c, 0.0) >
                                     node_gap(obstacles, mesh.vertices[v], it->second, 0.0))
        node_of[v] = c;  // (a larger g: the obstacle is nearer)
    }
  ContactSet s;
  const int dim = mesh.dim;
  for (const auto& [v, c] : node_of) {
    const int node = static_cast<int>(s.nodes.size());
    s.nodes.push_back(c);
    std::array<int, 3> i{-1, -1, -1};
    for (int k = 0; k < dim; ++k) {
      i[k] = bc.free_index(W.vertex_dof(v, k));
      if (i[k] >= 0) s.contact_dofs.push_back(i[k]);
    }
    // friction needs the tangential unknown: rotated even against an axis-aligned plane
    const bool rotate = rotate_always || obstacles[c.obstacle].friction.law != FrictionLaw::None;
    constrain_vertex(v, node, c.normal, i, dim, W, UD, rotate, s);
  }
  return s;
}

// Writes the bounds of K̄^h(t) into lower, upper.
void write_bounds(const Mesh& mesh, const std::vector<RigidObstacle>& obstacles, const ContactSet& set, double t,
                  Eigen::VectorXd& lower, Eigen::VectorXd& upper) {
  for (const Bound& b : set.bounds) {
    const ConstrainedProblem::ContactNode& c = set.nodes[b.node];
    const double g = node_gap(obstacles, mesh.vertices[c.vertex], c, t);
    // (g alone when factor = 1, offset = 0: the plane's −(a − p)·n to the last bit)
    const double value = b.factor == 1.0 && b.offset == 0.0 ? g : b.factor * g + b.offset;
    (b.lower ? lower : upper)[b.index] = value;
  }
}

// The friction nodes of the contact vertices whose obstacle has friction and which have
// a free tangential direction (the frames: every component free, or a roller in space;
// problems/friction.hpp): μ(a) (over |m| on a roller), or s_a = ∫_{Γ_C} s φ_a, the
// threshold integrated over the obstacle's contact parts against the vertex's basis
// function (assemble_boundary_load with the traction (s, 0)).
std::vector<FrictionNode> friction_nodes(const Mesh& mesh, const FESpace& W, const std::vector<RigidObstacle>& obstacles,
                                         const ContactSet& set) {
  std::vector<FrictionNode> out;
  std::vector<Eigen::VectorXd> share(obstacles.size());
  for (const ContactSet::Frame& fr : set.frames) {
    const ConstrainedProblem::ContactNode& c = set.nodes[fr.node];
    const FrictionSpec& spec = obstacles[c.obstacle].friction;
    if (spec.law == FrictionLaw::None) continue;
    const Point& a = mesh.vertices[c.vertex];
    FrictionNode f{fr.node, fr.normal, fr.tangential, spec.law};
    if (spec.law == FrictionLaw::Coulomb) {
      f.mu = spec.mu(a, 0.0);
      if (!(f.mu >= 0.0) || !std::isfinite(f.mu))
        throw InputError("friction_mu", "the friction coefficient must be finite and ≥ 0 (" + obstacles[c.obstacle].name + ")");
      f.mu /= fr.normal_share;  // |λ_T| ≤ μ λ_N with λ_N = (reaction on the normal unknown)/|m|
    } else {
      const double s = spec.threshold(a, 0.0);
      if (!(s >= 0.0)) throw InputError("friction_threshold", "the Tresca threshold must be ≥ 0 (" + obstacles[c.obstacle].name + ")");
      if (std::isinf(s)) {
        f.threshold = s;  // bonded (∞ · φ_a would be NaN where φ_a = 0)
      } else {
        Eigen::VectorXd& w = share[c.obstacle];
        if (w.size() == 0) {
          std::vector<Field> g(mesh.dim, Field(zero_field));
          g[0] = spec.threshold;
          w = assemble_boundary_load(W, obstacles[c.obstacle].contact_parts, g, 0.0);
        }
        f.threshold = w[W.vertex_dof(c.vertex, 0)];
        if (!(f.threshold >= 0.0) || !std::isfinite(f.threshold))
          throw InputError("friction_threshold", "the Tresca threshold must be finite and ≥ 0 on Γ_C, or ∞ (" +
                                                     obstacles[c.obstacle].name + ")");
      }
    }
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace

Lame lame_parameters(double E, double nu) {
  if (!(E > 0.0) || !std::isfinite(E)) throw InputError("E", "Young's modulus must be positive");
  if (!(nu > -1.0 && nu < 0.5)) throw InputError("nu", "Poisson's ratio must lie in (−1, ½)");
  return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
}

CellMaterials cell_materials(const Mesh& mesh, const ElasticContactData& d) {
  const Material body{d.rho, d.lambda, d.mu};
  check_material(body, "", mesh.dim);
  if (d.region_materials.empty()) return {d.rho, d.lambda, d.mu};
  const int n_regions = static_cast<int>(mesh.region_names.size());
  std::vector<const Material*> of_region(n_regions, nullptr);
  for (const auto& [r, m] : d.region_materials) {
    if (r < 0 || r >= n_regions || mesh.cell_region.empty())
      throw InputError("regions", "region " + std::to_string(r) + " is not a region of the mesh (it has " +
                                      std::to_string(n_regions) + ")");
    if (of_region[r]) throw InputError("regions", "region '" + mesh.region_names[r] + "' is given two materials");
    check_material(m, " (region '" + mesh.region_names[r] + "')", mesh.dim);
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
  return -((a.x - d.obstacle_point.x) * n.x + (a.y - d.obstacle_point.y) * n.y + (a.z - d.obstacle_point.z) * n.z);
}

std::vector<RigidObstacle> obstacles_of(const ElasticContactData& d) {
  if (!d.obstacles.empty()) return d.obstacles;
  if (d.contact_parts.empty()) return {};
  return {RigidObstacle::plane(d.obstacle_point, d.obstacle_normal, d.contact_parts)};
}

ConstrainedProblem build_elastic_contact(const Mesh& mesh, const ElasticContactData& d) {
  if (mesh.dim != 2 && mesh.dim != 3) throw InputError("mesh", "elasticity needs a 2D (plane strain) or 3D mesh");
  const int dim = mesh.dim;
  const CellMaterials material = cell_materials(mesh, d);
  const std::vector<RigidObstacle> obstacles = obstacles_of(d);
  if (d.obstacle && obstacles.empty()) throw InputError("contact", "elasticity with an obstacle needs a contact part Γ_C");
  for (const RigidObstacle& o : obstacles)
    if (o.contact_parts.empty()) throw InputError("contact", o.name + ": no contact part Γ_C");
  ConstrainedProblem p;
  p.W = std::make_unique<FESpace>(mesh, d.mass.W, dim);
  const FESpace& W = *p.W;
  p.bc = std::make_unique<DirichletLift>(W, d.dirichlet_parts, d.dirichlet_components);
  p.A_full = assemble_elasticity(W, material.lambda, material.mu);

  // L(t) = ∫_Ω (f + ρ g)·φ_i + ∫_{Γ_N} g_N·φ_i.  One density: ρ g is added to f at the
  // quadrature points; several: ∫ ρ g·φ_i is a load of its own, weighted cell by cell.
  std::vector<Field> f(d.f.begin(), d.f.begin() + dim);
  const std::vector<Field> gN(d.traction.begin(), d.traction.begin() + dim);
  const std::vector<int> neumann = d.neumann_parts;
  const std::vector<double> g(d.gravity.begin(), d.gravity.begin() + dim);
  const CellCoefficient rho = material.rho;
  if (rho.is_uniform())
    for (int k = 0; k < dim; ++k) {
      Field with_weight = [fk = f[k], rho_g = rho.value() * g[k]](const Point& x, double t) { return fk(x, t) + rho_g; };
      if (!f[k].depends_on_space()) with_weight.uniform_in_space();
      f[k] = with_weight;
    }
  bool weighted_gravity = false;
  for (double gk : g) weighted_gravity = weighted_gravity || (!rho.is_uniform() && gk != 0.0);
  p.L_full = [&W, body = load_in_time(W, f, !d.load_is_constant), gN, neumann, g, rho, weighted_gravity](double t) {
    Eigen::VectorXd L = body(t);
    if (weighted_gravity) {
      std::vector<Field> gk;
      for (double value : g) gk.push_back(Field([value](const Point&, double) { return value; }).uniform_in_space());
      L += assemble_load(W, rho, gk, t);
    }
    if (!neumann.empty()) L += assemble_boundary_load(W, neumann, gN, t);
    return L;
  };
  p.load_is_constant = d.load_is_constant;
  p.UD = d.dirichlet_parts.empty()
             ? Eigen::VectorXd::Zero(W.n_dofs())
             : p.bc->lifting(W, std::vector<Field>(d.dirichlet_value.begin(), d.dirichlet_value.begin() + dim));
  const SparseMatrix A_ff = p.bc->restrict(p.A_full);

  // K̄^h.  The contact set (and the rotation) is built even when the obstacle is
  // disabled: the redistributed mass depends on it, and the unconstrained run must
  // keep the same M and the same unknowns.
  const ContactSet contact = contact_set(mesh, W, *p.bc, p.UD, obstacles, d.rotate_always);
  const double inf = std::numeric_limits<double>::infinity();
  p.lower = Eigen::VectorXd::Constant(A_ff.rows(), -inf);
  p.upper = Eigen::VectorXd::Constant(A_ff.rows(), inf);
  p.contact_nodes = contact.nodes;
  p.obstacles = obstacles;
  if (d.obstacle) {
    write_bounds(mesh, obstacles, contact, 0.0, p.lower, p.upper);
    for (const Bound& b : contact.bounds) p.constrained.push_back(b.index);
    p.friction = friction_nodes(mesh, W, obstacles, contact);
    bool moves = false;
    for (const RigidObstacle& o : obstacles) moves = moves || o.moves;
    if (moves)
      p.moving_bounds = [&mesh, obstacles, contact](double t, Eigen::VectorXd& lower, Eigen::VectorXd& upper) {
        write_bounds(mesh, obstacles, contact, t, lower, upper);
      };
  }

  // Redistributed mass: every component of each contact node is massless, so every
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
