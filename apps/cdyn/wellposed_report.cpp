// wellposed_report.cpp — condition (12) for a run's pair and constraints.
//
// β = σ_min(G Z) is computed at any size (wellposedness/condition12.hpp: dense up to 150
// dofs, sparse Cholesky factorizations and Lanczos above, about a minute at 1M dofs); a
// run reports why it was not computed only when the check does not apply (rollers) or a
// factorization fails (out of memory).
#include <cstdio>

#include "cdyn/base/error.hpp"
#include "cdyn/wellposedness/condition12.hpp"
#include "commands.hpp"
#include "simulation.hpp"

namespace cdyn::app {

WellPosednessSetup wellposedness_setup(const Simulation& sim) {
  if (!sim.dirichlet_components.empty())
    throw InputError("dirichlet.components: rollers are not supported by the check of condition (12)");
  WellPosednessSetup setup;
  setup.dirichlet_parts = sim.dirichlet_parts;
  setup.components = sim.components;
  if (sim.partition) {  // the whole mesh's, gathered on the first rank (partition.hpp)
    setup.constrained_vertices = sim.partition->constrained_vertices;
    if (sim.components > 1) setup.normals = sim.partition->normals;
    return setup;
  }
  setup.constrained_vertices = sim.constrained_vertices;
  if (sim.components > 1) {  // the normal of the obstacle at each constrained vertex
    for (int v : setup.constrained_vertices)
      for (const auto& c : sim.problem.contact_nodes)
        if (c.vertex == v) setup.normals.push_back(c.normal);
  }
  return setup;
}

nlohmann::ordered_json wellposedness_summary(const Simulation& sim) {
  nlohmann::ordered_json j;
  try {
    const Mesh& mesh = sim.partition ? sim.partition->whole : *sim.mesh;  // (on subdomains, the first rank's)
    const WellPosedness w = condition12_on(mesh, sim.spec.method.mass, wellposedness_setup(sim));
    j["beta"] = w.beta;
    j["satisfied"] = w.satisfied;
    j["dim_ker_B"] = w.dim_ker_B;
    j["n_g"] = w.n_g;
    j["method"] = w.method;
  } catch (const std::runtime_error& e) {  // InputError (does not apply), NumericalError (factorization)
    j["beta"] = nullptr;
    j["satisfied"] = nullptr;
    j["not_computed"] = e.what();
  }
  return j;
}

std::string wellposedness_line(const nlohmann::ordered_json& w) {
  if (w["beta"].is_null()) return "not computed (" + w["not_computed"].get<std::string>() + ")";
  char buf[128];
  std::snprintf(buf, sizeof buf, "beta = %.3e, %s", w["beta"].get<double>(),
                w["satisfied"].get<bool>() ? "satisfied" : "VIOLATED (the semi-discrete problem is not well posed)");
  return buf;
}

}  // namespace cdyn::app
