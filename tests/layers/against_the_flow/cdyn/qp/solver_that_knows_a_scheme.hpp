// A file the layer check must refuse: a step QP solver that includes a time scheme
// (the QP stage sees only S, r and the bounds).  Used by the CTest kernel_layers_refuses.
#pragma once

#include "cdyn/schemes/time_scheme.hpp"
