// problems/subdomain.hpp — where a subdomain's unknowns sit in the whole problem: the map
// P_r of mesh/sub_mesh.hpp's identities A = Σ_r P_rᵀ A_r P_r, L = Σ_r P_rᵀ L_r.
//
// The problem built on the sub-mesh of subdomain r (the same data, mesh/sub_mesh.hpp)
// numbers its free dofs as the kernel does on any mesh; a vertex dof is the whole
// problem's dof of the same vertex (SubMesh::vertex) and component, a bubble dof that of
// the same cell (SubMesh::cell).  Vertex dofs and bubbles only: the spaces P1 and P1+.
#pragma once

#include <vector>

#include "cdyn/mesh/sub_mesh.hpp"
#include "cdyn/problems/constrained_problem.hpp"

namespace cdyn {

// The whole problem's free unknown of each of `part`'s (built on sub.mesh from the
// whole's data), the whole problem given by its space W on the whole mesh and its
// Dirichlet dofs bc (nothing assembled).  InputError for a space other than P1 and P1+,
// or an unknown free in the part and fixed in the whole (the sub-mesh was not made from
// the whole's mesh).
std::vector<int> unknowns_in_whole(const FESpace& W, const DirichletLift& bc, const ConstrainedProblem& part,
                                   const SubMesh& sub);

}  // namespace cdyn
