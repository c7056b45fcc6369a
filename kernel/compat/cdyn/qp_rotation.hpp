// qp_rotation.hpp — forwarding header: the flat include path of cdyn 0.1 before the kernel was
// laid out by stage (docs/kernel_map.md).  Kept for one release; include the new path.
#pragma once

#include "cdyn/problems/nodal_rotation.hpp"
#include "cdyn/qp/rotated_qp.hpp"

