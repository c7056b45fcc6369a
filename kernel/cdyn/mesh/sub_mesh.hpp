// mesh/sub_mesh.hpp — the part of a mesh made of some of its cells: one subdomain of a
// partition of the cells, the unit of a distributed assembly.
//
// Every matrix and vector of the kernel is a sum over cells (A = Σ_K A_K, the load, the
// mixed pairs' B and C, and with them M = Bᵀ C⁻¹ B whenever C is block diagonal by
// cell, as for H^h = P0), and so is the step matrix after the bubbles are condensed
// (each bubble lives in one cell: qp/condensation.hpp).  Built on the sub-mesh Ω_r of
// the cells of subdomain r, the same problem therefore gives that subdomain's share,
// and the whole problem's is the sum over subdomains, each share placed by the map P_r
// from the sub-mesh's vertices to the mesh's:
//     A = Σ_r P_rᵀ A_r P_r,    L = Σ_r P_rᵀ L_r.
// What must not be split is what acts on vertices: a vertex of Ω_r on a Dirichlet or
// contact part is constrained in every subdomain that holds it, even where the part's
// facets belong to another subdomain's cells (a vertex of Ω_r that only touches the
// part).  The sub-mesh keeps the boundary facets of its own cells (so that a traction
// is integrated once) and lists the others' part vertices in Mesh::parts_elsewhere.
//
// Only vertex dofs are seen across subdomains this way: a P2 edge dof on a part whose
// facet another subdomain holds is not (the distributed runs take P1 and P1+ spaces).
#pragma once

#include <vector>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

struct SubMesh {
  Mesh mesh;                // the cells, their vertices numbered in the mesh's order
  std::vector<int> vertex;  // the mesh's vertex of each of the sub-mesh's (increasing)
  std::vector<int> cell;    // the mesh's cell of each of the sub-mesh's (as given)
};

// The sub-mesh of `cells` (indices into mesh.cells, each once).  InputError if one is
// out of range or repeated.
SubMesh sub_mesh(const Mesh& mesh, const std::vector<int>& cells);

// The cells whose centroid lies in slab `part` of `parts` equal slabs across the mesh's
// x-range: a partition of the cells, the tests' and the benchmarks' (a graph
// partitioner cuts fewer couplings on a general mesh).
std::vector<int> slab_cells(const Mesh& mesh, int part, int parts);

// The cells' dual graph: two cells are neighbours when they share a facet.  In CSR form:
// the neighbours of cell c are neighbour[offset[c]] … neighbour[offset[c + 1] − 1], in
// increasing order.  What a graph partitioner cuts (qp/petsc/backend.hpp's
// partition_graph): a subdomain's interface is the facets between its cells and others'.
struct CellGraph {
  std::vector<int> offset, neighbour;
};
CellGraph cell_graph(const Mesh& mesh);

}  // namespace cdyn
