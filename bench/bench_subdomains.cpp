// bench_subdomains.cpp — the unit cube's time loop on subdomains: each rank builds the
// problem of its own slab of cells (mesh/sub_mesh.hpp) and steps the scheme on it, the
// step QP summed from the ranks' shares and solved by the PETSc back end
// (qp/petsc/backend.hpp, make_petsc_subdomain_solver), against the whole problem on one
// process with the native CG path (docs/distributed.md, "Subdomains").
//
// The scene of data/scenes/cube_3d.toml: E = 1, ν = 0.3, ρ = 1, P1+/P0, falling at 0.1
// onto the plane z = −h/2, dt = h/2, the midpoint rule with its full-step
// reconstruction (eq. 14; by CG alone on the native path, as `cdyn run` takes it there),
// tol 1e-10.
// Not a Google Benchmark: every rank must run the same steps (collective solves).
//
//   mpirun -n P build/bench/bench_subdomains N STEPS [PC]       (subdomains, P ranks; PC: jacobi
//                                                                 (default), hypre or gamg)
//   build/bench/bench_subdomains N STEPS native                  (the whole problem)
// prints per rank its cells and unknowns, its set-up, the mean step and QP time over
// steps 6..STEPS (contact from step 6), and its peak memory; then the energy J(T).
#include <malloc.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/mesh/sub_mesh.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/problems/subdomain.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "cdyn/schemes/time_scheme.hpp"

using namespace cdyn;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

double peak_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

ElasticContactData cube_data(double h) {
  ElasticContactData d;
  d.mass = MassSpec::pair(Element::P1Bubble, Element::P0);
  const Lame lame = lame_parameters(1.0, 0.3);
  d.lambda = lame.lambda, d.mu = lame.mu;
  d.contact_parts = {4};  // "bottom"
  d.obstacle_point = {0.0, 0.0, -h / 2};
  d.obstacle_normal = {0.0, 0.0, 1.0};
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_subdomains N STEPS [native | jacobi | hypre | gamg]\n");
    return 2;
  }
  // freed memory kept in the heap, as the cdyn program does (apps/cdyn/main.cpp: glibc
  // would map and unmap every block above 32 MB, a third of a large set-up)
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
  const int n = std::atoi(argv[1]), steps = std::atoi(argv[2]);
  const bool native = argc > 3 && std::string(argv[3]) == "native";
  const std::string pc = argc > 3 && !native ? argv[3] : "";
  if (!native) petsc::initialize();
  const int me = petsc::rank(), ranks = petsc::size();
  const auto start = std::chrono::steady_clock::now();

  const Mesh mesh = unit_cube_mesh(n);
  const double h = 1.0 / n, dt = h / 2;
  const ElasticContactData d = cube_data(h);
  QPOptions options;
  options.tol = 1e-10;
  options.pdas_cg_only = native;  // the native CG path (solver.linear = "cg")
  SchemeParameters parameters;
  parameters.reconstruct_by_cg = native;
  parameters.tol = options.tol;

  SubMesh sub;
  if (!native) sub = sub_mesh(mesh, slab_cells(mesh, me, ranks));
  const ConstrainedProblem p = build_elastic_contact(native ? mesh : sub.mesh, d);
  std::unique_ptr<StepSolver> solver;
  if (native) {
    solver = make_step_solver("pdas", options);
  } else {
    const FESpace W(mesh, Element::P1Bubble, 3);  // the whole problem's numbering, nothing assembled
    const DirichletLift bc(W, {});
    solver = petsc::make_petsc_subdomain_solver(unknowns_in_whole(W, bc, p, sub), options, pc);
  }
  auto scheme = make_time_scheme("midpoint", p, *solver, dt, parameters);
  State s;
  s.U = Eigen::VectorXd::Zero(p.n_free());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(p.n_free());  // the field (0, 0, −0.1): z of the vertex dofs
  const int vertex_unknowns = 3 * (native ? mesh : sub.mesh).n_vertices();
  for (int i = 2; i < vertex_unknowns; i += 3) w[i] = -0.1;
  s.V = p.mass->velocity(w);
  const double setup = seconds_since(start);

  double step_sum = 0, qp_sum = 0;
  int counted = 0, held = 0;
  for (int k = 1; k <= steps; ++k) {
    const auto t = std::chrono::steady_clock::now();
    const StepStats st = scheme->step(s);
    const double step = seconds_since(t);
    if (k >= 6) step_sum += step, qp_sum += st.qp_seconds, ++counted;
    held = std::max(held, st.active);
  }
  const double J = petsc::sum_over_ranks(scheme->energy(s).total());
  std::printf("rank %d of %d%s: %d cells, %d unknowns; set-up %.3f s; step %.4f s, QP %.4f s (mean of steps 6-%d); "
              "held %d; peak %.0f MB\n",
              me, ranks, native ? " (native CG path)" : "", (native ? mesh : sub.mesh).n_cells(), p.n_free(), setup,
              step_sum / counted, qp_sum / counted, steps, held, peak_mb());
  if (me == 0) std::printf("J(T) = %.15g\n", J);
  return petsc::end_process(0);
}
