// commands.hpp — the subcommands of the `cdyn` command line (one file each).
// Each returns the process exit status; bad input is thrown as cdyn::InputError and
// turned into one line and exit status 2 by main().
#pragma once

#include <string>

namespace cdyn::app {

// `cdyn mesh FILE.geo|FILE.msh`: counts, measure, h and the physical groups.
int cmd_mesh(const std::string& file);

}  // namespace cdyn::app
