// entries.hpp — the functions the fuzz targets feed their inputs to, shared with the
// regression test that replays the crashing inputs kept in tests/robustness/regressions
// (so a normal gcc build re-checks them without clang or libFuzzer).
//
// Each entry takes arbitrary bytes and must return normally.  Bad input is expected
// and ends in cdyn::InputError (the command line's exit status 2), caught here; a
// numerical failure of the first steps (cdyn::NumericalError, exit status 3) is
// accepted too.  Anything else — another exception, a crash, a sanitizer report, a
// hang — is a finding.
#pragma once

#include <string_view>

namespace cdyn::fuzz {

// A scene file's text (TOML), with optional override lines "#set key=value" (TOML
// comments, applied through Scene::set), through make_simulation and two time steps.
// Inputs that would request a large problem are skipped (size caps below), so that a
// fuzz input cannot make one execution take seconds; the product has no such cap.
void scene_input(std::string_view text);

// An expression (physics.f, initial.u, ...) parsed and evaluated at a few points.
void expression_input(std::string_view text);

// A .msh file's text, written to a temporary file and read with read_mesh.
void mesh_input(std::string_view text);

// The caps of scene_input: cells per side of a unit square and of a unit cube, cells of
// an interval.
inline constexpr int kMaxSquareCells = 8, kMaxCubeCells = 3, kMaxIntervalCells = 64;

}  // namespace cdyn::fuzz
