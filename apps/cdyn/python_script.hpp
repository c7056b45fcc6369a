// python_script.hpp — running an embedded python3-matplotlib script on a directory.
//
// The plots are optional (docs/outputs.md: made when python3-matplotlib is present), so
// nothing here is an error: a missing interpreter, a missing matplotlib or a failing
// script each give one note line, and the run goes on.
#pragma once

#include <string>
#include <vector>

namespace cdyn::app {

// Runs `python3 -c SCRIPT ARGS...`.  The interpreter is $CDYN_PYTHON when set, else
// the first of `python3` (on PATH) and /usr/bin/python3 (Debian's, where
// python3-matplotlib installs) that has matplotlib: the scripts exit with status 3
// when `import matplotlib` fails, and the next interpreter is tried.  Returns an
// empty string on success, else the note to print (what was missing or failed).
std::string run_python_script(const char* script, const std::vector<std::string>& args);

}  // namespace cdyn::app
