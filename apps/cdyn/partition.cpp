// partition.cpp — a run on subdomains; see partition.hpp.
#include "partition.hpp"

#include <algorithm>
#include <limits>

#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/problems/subdomain.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "simulation.hpp"

namespace cdyn::app {

namespace {

// The owner of each of n items (the lowest rank holding it) from the items this rank
// holds: a mask of those it owns among them.
std::vector<char> owned_items(const std::vector<int>& held, int n) {
  std::vector<double> owner(n, std::numeric_limits<double>::infinity());
  const double me = petsc::rank();
  for (int g : held) owner[g] = me;
  petsc::reduce_over_ranks(owner, petsc::Reduction::min);
  std::vector<char> mine(held.size());
  for (std::size_t i = 0; i < held.size(); ++i) mine[i] = owner[held[i]] == me;
  return mine;
}

// The cells of this rank in PT-Scotch's partition of the cells' dual graph.
std::vector<int> graph_cells(const Mesh& mesh) {
  const CellGraph g = cell_graph(mesh);
  const std::vector<int> rank_of = petsc::partition_graph(g.offset, g.neighbour);
  std::vector<int> cells;
  for (int c = 0; c < mesh.n_cells(); ++c)
    if (rank_of[c] == petsc::rank()) cells.push_back(c);
  return cells;
}

// The cells `cells` of this rank, checked to deal out every cell of the mesh once over
// the ranks (collective).
std::vector<int> given_cells(const Mesh& mesh, const std::vector<int>& cells) {
  std::vector<double> count(mesh.n_cells(), 0.0);
  bool valid = true;
  for (int c : cells) {
    valid = valid && c >= 0 && c < mesh.n_cells();
    if (valid) count[c] += 1.0;
  }
  petsc::reduce_over_ranks(count, petsc::Reduction::sum);
  valid = petsc::max_over_ranks(valid ? 0.0 : 1.0) == 0.0;
  if (!valid || std::any_of(count.begin(), count.end(), [](double n) { return n != 1.0; }))
    throw InputError("solver.partition: the ranks' cells in the checkpoint do not deal out the mesh's cells once "
                     "each (resume on as many ranks as the stopped run had)");
  return cells;
}

}  // namespace

Partition make_partition(Mesh whole, const std::string& how, const std::vector<int>* cells) {
  Partition part;
  part.sub = sub_mesh(whole, cells                ? given_cells(whole, *cells)
                             : how == "graph" ? graph_cells(whole)
                                              : slab_cells(whole, petsc::rank(), petsc::size()));
  // (a rank without cells would have no problem to build: refused on every rank at once)
  if (petsc::max_over_ranks(part.sub.cell.empty() ? 1.0 : 0.0) > 0.0)
    throw InputError("solver.partition: a rank has no cells (" + std::to_string(petsc::size()) + " ranks for " +
                     std::to_string(whole.n_cells()) + " cells): run on fewer ranks or refine the mesh");
  part.local_cell.assign(whole.n_cells(), -1);
  for (std::size_t c = 0; c < part.sub.cell.size(); ++c) part.local_cell[part.sub.cell[c]] = static_cast<int>(c);
  part.local_vertex.assign(whole.n_vertices(), -1);
  for (std::size_t v = 0; v < part.sub.vertex.size(); ++v) part.local_vertex[part.sub.vertex[v]] = static_cast<int>(v);
  part.owns_vertex = owned_items(part.sub.vertex, whole.n_vertices());
  std::vector<double> holders(whole.n_vertices(), 0.0);
  for (int v : part.sub.vertex) holders[v] = 1.0;
  petsc::reduce_over_ranks(holders, petsc::Reduction::sum);
  part.interface_vertices = static_cast<int>(std::count_if(holders.begin(), holders.end(), [](double h) { return h > 1; }));
  part.whole = std::move(whole);
  return part;
}

void number_unknowns(Simulation& sim) {
  Partition& part = *sim.partition;
  const FESpace& W = *sim.problem.W;
  // the whole problem's numbering: its space and Dirichlet dofs, nothing assembled
  const FESpace W_whole(part.whole, W.element(), W.components());
  const DirichletLift bc(W_whole, sim.dirichlet_parts, sim.dirichlet_components);
  part.in_whole = unknowns_in_whole(W_whole, bc, sim.problem, part.sub);
  part.whole_dofs = W_whole.n_dofs();
  part.whole_free = static_cast<int>(bc.free_dofs().size());
  part.owns_unknown = owned_items(part.in_whole, part.whole_free);
  // the constrained vertices each rank owns, with their normals, gathered on the first
  std::vector<double> mine;
  for (int v : sim.constrained_vertices) {
    if (!part.owns_vertex[v]) continue;
    Point n;
    for (const auto& c : sim.problem.contact_nodes)
      if (c.vertex == v) n = c.normal;
    mine.insert(mine.end(), {static_cast<double>(part.sub.vertex[v]), n.x, n.y, n.z});
  }
  const std::vector<double> all = petsc::gather_on_first_rank(mine);
  std::vector<std::pair<int, Point>> found;
  for (std::size_t k = 0; k < all.size(); k += 4)
    found.emplace_back(static_cast<int>(all[k]), Point{all[k + 1], all[k + 2], all[k + 3]});
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [v, n] : found) {
    part.constrained_vertices.push_back(v);
    part.normals.push_back(n);
  }
}

ProblemSizes whole_sizes(const Simulation& sim) {
  const ConstrainedProblem& p = sim.problem;
  if (!sim.partition)
    return {p.W->n_dofs(), p.n_free(), p.mass->n_velocity(), static_cast<int>(p.constrained.size()), sim.mesh->h_max()};
  const Partition& part = *sim.partition;
  ProblemSizes n{part.whole_dofs, part.whole_free, 0, 0, part.whole.h_max()};
  int constraints = 0;
  for (int i : p.constrained) constraints += part.owns_unknown[i];
  n.constraints = static_cast<int>(summed(sim, constraints));
  // velocities per cell (H^h = P0) are each one rank's; those of a mass on W^h are the
  // free unknowns; a continuous H^h takes the saddle form, refused on subdomains
  const MassSpec& mass = sim.spec.method.mass;
  n.velocity = !mass.is_pair() ? n.free : static_cast<int>(summed(sim, p.mass->n_velocity()));
  return n;
}

double summed(const Simulation& sim, double x) { return sim.partition ? petsc::sum_over_ranks(x) : x; }

double largest(const Simulation& sim, double x) { return sim.partition ? petsc::max_over_ranks(x) : x; }

Energy summed(const Simulation& sim, const Energy& E) {
  if (!sim.partition) return E;
  std::vector<double> e{E.kinetic, E.potential};
  petsc::reduce_over_ranks(e, petsc::Reduction::sum);
  return {e[0], e[1]};
}

void summed(const Simulation& sim, std::vector<double>& x) {
  if (sim.partition) petsc::reduce_over_ranks(x, petsc::Reduction::sum);
}

Point summed(const Simulation& sim, const Point& x) {
  std::vector<double> v{x.x, x.y, x.z};
  summed(sim, v);
  return {v[0], v[1], v[2]};
}

bool writes_files(const Simulation& sim) { return !sim.partition || petsc::rank() == 0; }

bool on_any_rank(const Simulation& sim, bool b) { return largest(sim, b ? 1.0 : 0.0) > 0.0; }

Eigen::VectorXd owned_part(const Simulation& sim, const Eigen::VectorXd& x) {
  if (!sim.partition || x.size() == 0) return x;
  Eigen::VectorXd out = x;
  for (Eigen::Index i = 0; i < out.size(); ++i)
    if (!sim.partition->owns_unknown[i]) out[i] = 0.0;
  return out;
}

namespace {

// Integrals over Γ_C at contact vertices of this rank's mesh (its own facets' shares),
// each summed over the ranks holding its vertex: the whole Γ_C's (collective).  A vertex
// has one contact node (the nearest obstacle's, problems/elastic_contact.hpp).
std::vector<double> over_whole_boundary(const Simulation& sim, const std::vector<int>& vertices,
                                        const std::vector<double>& shares) {
  const SubMesh& sub = sim.partition->sub;
  std::vector<double> whole(sim.partition->whole.n_vertices(), 0.0);
  for (std::size_t i = 0; i < vertices.size(); ++i) whole[sub.vertex[vertices[i]]] += shares[i];
  summed(sim, whole);
  std::vector<double> out;
  for (int v : vertices) out.push_back(whole[sub.vertex[v]]);
  return out;
}

}  // namespace

std::vector<double> whole_contact_weights(const Simulation& sim, const ContactPressure& contact) {
  std::vector<int> vertices;
  std::vector<double> w;
  for (const ContactPressure::Vertex& c : contact.vertices()) vertices.push_back(c.vertex), w.push_back(c.weight);
  return sim.partition ? over_whole_boundary(sim, vertices, w) : w;
}

void whole_friction_thresholds(Simulation& sim) {
  if (!sim.partition || !sim.with_friction) return;
  ConstrainedProblem& p = sim.problem;
  std::vector<int> vertices;
  std::vector<double> s;  // (0 for Coulomb's nodes, whose threshold is μ λ_N)
  for (const FrictionNode& f : p.friction) {
    vertices.push_back(p.contact_nodes[f.node].vertex);
    s.push_back(f.law == FrictionLaw::Tresca ? f.threshold : 0.0);
  }
  s = over_whole_boundary(sim, vertices, s);
  for (std::size_t k = 0; k < p.friction.size(); ++k)
    if (p.friction[k].law == FrictionLaw::Tresca) p.friction[k].threshold = s[k];
}

namespace {

// The arrays' tuples of the listed items (`mine`: those this rank sends, all when empty),
// each after its index in the whole (`whole_of`), gathered on the first rank and placed
// at their indices among n items.
std::vector<FieldArray> gathered(const std::vector<FieldArray>& arrays, const std::vector<int>& whole_of,
                                 const std::vector<char>& mine, int n) {
  int width = 1;  // the index, then every array's components
  for (const FieldArray& a : arrays) width += a.components;
  std::vector<double> sent;
  for (std::size_t i = 0; i < whole_of.size(); ++i) {
    if (!mine.empty() && !mine[i]) continue;
    sent.push_back(whole_of[i]);
    for (const FieldArray& a : arrays)
      sent.insert(sent.end(), a.values.begin() + i * a.components, a.values.begin() + (i + 1) * a.components);
  }
  const std::vector<double> all = petsc::gather_on_first_rank(sent);
  std::vector<FieldArray> out;
  for (const FieldArray& a : arrays)
    out.push_back({a.name, a.components, std::vector<double>(static_cast<std::size_t>(n) * a.components, 0.0)});
  for (std::size_t k = 0; k < all.size(); k += width) {
    const std::size_t item = static_cast<std::size_t>(all[k]);
    std::size_t at = k + 1;
    for (FieldArray& a : out) {
      std::copy(all.begin() + at, all.begin() + at + a.components, a.values.begin() + item * a.components);
      at += a.components;
    }
  }
  return out;
}

}  // namespace

ExtraFields gathered_on_first_rank(const Simulation& sim, const ExtraFields& local) {
  const Partition& part = *sim.partition;
  ExtraFields whole{gathered(local.point, part.sub.vertex, part.owns_vertex, part.whole.n_vertices()),
                    gathered(local.cell, part.sub.cell, {}, part.whole.n_cells())};
  if (petsc::rank() != 0) return {};
  return whole;
}

}  // namespace cdyn::app
