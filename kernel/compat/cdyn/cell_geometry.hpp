// cell_geometry.hpp — forwarding header: the flat include path of cdyn 0.1 before the kernel was
// laid out by stage (docs/kernel_map.md).  Kept for one release; include the new path.
#pragma once

#include "cdyn/mesh/cell_geometry.hpp"

