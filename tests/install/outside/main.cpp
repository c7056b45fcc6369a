// main.cpp — the smallest program against an installed cdyn: one call into each of the
// three libraries.
//
//   cdyn::cdyn     condition (12) of the seed for P1+/P0 on the membrane of its
//                  experiments (unit square, n = 10, u fixed on the boundary, u ≥ g at
//                  every vertex): β = σ_min(G Z) = 0.3090 (the figure `cdyn wellposed
//                  --set mesh.n=10` prints, tests/cli/CMakeLists.txt, cli_wellposed);
//   cdyn::meshing  read_mesh of a .geo through gmsh (the L-shape, area 0.75), by the
//                  installed plugin PREFIX/lib/cdyn/libcdyn_gmsh.so;
//   cdyn::io       a FieldsWriter series of the initial state.
//
// Usage: outside LSHAPE.geo OUTDIR
#include <cdyn/cdyn.hpp>  // the umbrella header (below: the flat paths of 0.1, forwarding)
#include <cdyn/fields_output.hpp>
#include <cdyn/gmsh_mesh.hpp>
#include <cdyn/mesh.hpp>
#include <cdyn/scalar_wave.hpp>
#include <cdyn/version.hpp>
#include <cdyn/wellposedness.hpp>
#include <cstdio>
#include <numeric>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: outside LSHAPE.geo OUTDIR\n");
    return 2;
  }
  const cdyn::Mesh square = cdyn::unit_square_mesh(10);
  cdyn::WellPosednessSetup setup;
  setup.dirichlet_parts = {0, 1, 2, 3};
  setup.constrained_vertices.resize(square.n_vertices());
  std::iota(setup.constrained_vertices.begin(), setup.constrained_vertices.end(), 0);
  const cdyn::WellPosedness w = cdyn::condition12_on(square, cdyn::MassSpec::parse("P1+/P0"), setup);
  std::printf("cdyn %s\n", cdyn::version);
  std::printf("P1+/P0 n=10: N_W %d N_H %d dimKerB %d N_g %d beta %.4f satisfied %s\n", w.n_W, w.n_H, w.dim_ker_B,
              w.n_g, w.beta, w.satisfied ? "yes" : "no");

  const cdyn::Mesh lshape = cdyn::read_mesh(argv[1]);
  std::printf("lshape: %d vertices, %d cells, area %.12f\n", lshape.n_vertices(), lshape.n_cells(), lshape.measure());
  std::printf("gmsh plugin %s\n", cdyn::gmsh_plugin_file().c_str());

  cdyn::ScalarWaveData d;
  d.f = [](double, double, double) { return -1.0; };
  d.dirichlet_parts = {lshape.part_index("outer")};
  d.dirichlet_value = [](double, double, double) { return 0.02; };
  d.obstacle_g = [](double, double, double) { return 0.0; };
  const cdyn::ConstrainedProblem p = cdyn::build_scalar_wave(lshape, d);
  const Eigen::VectorXd U = p.W->interpolate([](double, double, double) { return 0.02; });
  cdyn::FieldsWriter out(argv[2], lshape, p);
  out.write(0, 0.0, U, Eigen::VectorXd::Zero(U.size()), Eigen::VectorXd());
  out.finish();
  std::printf("wrote %s/fields.pvd\n", argv[2]);
  return 0;
}
