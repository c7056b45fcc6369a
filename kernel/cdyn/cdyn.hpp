// cdyn.hpp — the whole kernel in one include, stage by stage in the order the data
// flows (docs/kernel_map.md): mesh → spaces → A, B, C, L → mass model and constraints
// → condition (12) → step QP → scheme → post-processing.  Teaching programs may prefer
// the single headers, which say what each stage needs.
#pragma once

// base/
#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/base/sparse.hpp"
// mesh/
#include "cdyn/mesh/cell_geometry.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/mesh/point_location.hpp"
// fe/
#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/fe/element.hpp"
#include "cdyn/fe/fe_space.hpp"
#include "cdyn/fe/field.hpp"
#include "cdyn/fe/norms.hpp"
#include "cdyn/fe/quadrature.hpp"
// linalg/
#include "cdyn/linalg/least_squares.hpp"
#include "cdyn/linalg/masked_cg.hpp"
#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/linalg/symmetric_gauss_seidel.hpp"
// mass/
#include "cdyn/mass/classical.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/mass/mass_spec.hpp"
#include "cdyn/mass/mixed.hpp"
#include "cdyn/mass/redistribution.hpp"
#include "cdyn/mass/rotated.hpp"
// problems/
#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/problems/nodal_rotation.hpp"
#include "cdyn/problems/oscillator.hpp"
#include "cdyn/problems/scalar_wave.hpp"
// exact/
#include "cdyn/exact/bar_exact.hpp"
// wellposedness/
#include "cdyn/wellposedness/condition12.hpp"
#include "cdyn/wellposedness/condition12_sparse.hpp"
#include "cdyn/wellposedness/lanczos.hpp"
#include "cdyn/wellposedness/row_basis.hpp"
#include "cdyn/wellposedness/shifted_gram.hpp"
// qp/
#include "cdyn/qp/bound_qp.hpp"
#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/condensation.hpp"
#ifdef CDYN_WITH_IPOPT
#include "cdyn/qp/ipopt.hpp"
#endif
#include "cdyn/qp/kkt.hpp"
#ifdef CDYN_WITH_NLOPT
#include "cdyn/qp/nlopt.hpp"
#endif
#include "cdyn/qp/pdas/explicit_reduced_system.hpp"
#include "cdyn/qp/pdas/pdas.hpp"
#include "cdyn/qp/pdas/projected_newton.hpp"
#include "cdyn/qp/pdas/reduced_system.hpp"
#include "cdyn/qp/pdas/reference_pdas.hpp"
#include "cdyn/qp/pdas/saddle_reduced_system.hpp"
#include "cdyn/qp/pgs.hpp"
#include "cdyn/qp/quadratic_form.hpp"
#include "cdyn/qp/rotated_qp.hpp"
#include "cdyn/qp/step_solver.hpp"
// schemes/
#include "cdyn/schemes/step_qp_scheme.hpp"
#include "cdyn/schemes/time_scheme.hpp"
// post/
#include "cdyn/post/contact_force.hpp"
#include "cdyn/post/contact_pressure.hpp"
#include "cdyn/post/impact_summary.hpp"
#include "cdyn/post/linear_momentum.hpp"
#include "cdyn/version.hpp"
