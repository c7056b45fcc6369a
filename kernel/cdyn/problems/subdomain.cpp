// problems/subdomain.cpp — a subdomain's unknowns in the whole problem (problems/subdomain.hpp).
#include "cdyn/problems/subdomain.hpp"

#include <string>

#include "cdyn/base/error.hpp"

namespace cdyn {

std::vector<int> unknowns_in_whole(const FESpace& W, const DirichletLift& bc, const ConstrainedProblem& part,
                                   const SubMesh& sub) {
  if (W.element() != Element::P1 && W.element() != Element::P1Bubble)
    throw InputError("subdomain: only P1 and P1+ displacements are split into subdomains (not " +
                     to_string(W.element()) + ")");
  const int k = W.components(), nv = sub.mesh.n_vertices(), nv_whole = W.mesh().n_vertices();
  std::vector<int> P;
  P.reserve(part.bc->free_dofs().size());
  for (int i : part.bc->free_dofs()) {
    const int s = i / k, component = i % k;
    const int whole_s = s < nv ? sub.vertex[s] : nv_whole + sub.cell[s - nv];  // a vertex, or a cell's bubble
    const int g = bc.free_index(W.dof(whole_s, component));
    if (g < 0) throw InputError("subdomain: a free unknown of the subdomain is fixed in the whole problem");
    P.push_back(g);
  }
  return P;
}

}  // namespace cdyn
