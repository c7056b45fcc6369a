// qp.hpp — forwarding header: the flat include path of cdyn 0.1 before the kernel was
// laid out by stage (docs/kernel_map.md).  Kept for one release; include the new path.
#pragma once

#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/qp/bound_qp.hpp"
#include "cdyn/qp/checks.hpp"
#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/quadratic_form.hpp"
#include "cdyn/qp/step_solver.hpp"

