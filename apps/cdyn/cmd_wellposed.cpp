// cmd_wellposed.cpp — `cdyn wellposed [SCENE] [--set ...] [--json]`: condition (12)
// for every pair on the scene's mesh and constraints.
//
// One row per pair W^h/H^h (and per classical mass model): N_W (free displacement
// dofs), N_H (velocity dofs), dim Ker B, N_g (constraints), β = σ_min(G Z) with Z an
// orthonormal basis of Ker B, and whether (12) holds (seed, "Sufficient condition
// for the well-posedness").  β is computed at any size (dense up to 150 dofs, sparse
// above: wellposedness/condition12.hpp); a model that does not apply (redistribution
// with a volume obstacle) or a failed factorization (out of memory) says why.
#include <cstdio>
#include <iostream>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/wellposedness/condition12.hpp"
#include "commands.hpp"
#include "simulation.hpp"

namespace cdyn::app {

nlohmann::ordered_json wellposed_rows(const Simulation& sim) {
  const WellPosednessSetup setup = wellposedness_setup(sim);  // elasticity: 2 components, the plane's normal
  // The pairs of the seed's experiments, in its order, then the classical masses (on P1).
  const std::vector<std::string> specs = {"P1/P1",      "P1/P0",  "P1+/P0",       "P1+/P1",
                                          "P2/P1",      "consistent", "lumped", "redistributed"};
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const std::string& spec : specs) {
    nlohmann::ordered_json row;
    row["pair"] = spec;
    try {
      const WellPosedness w = with_scene_keys(sim.spec, [&] {
        return condition12_on(*sim.mesh, MassSpec::parse(spec, Element::P1), setup);
      });
      row["N_W"] = w.n_W;
      row["N_H"] = w.n_H;
      row["dim_ker_B"] = w.dim_ker_B;
      row["N_g"] = w.n_g;
      row["beta"] = w.beta;
      row["satisfied"] = w.satisfied;
      row["method"] = w.method;
    } catch (const std::runtime_error& e) {  // InputError (does not apply), NumericalError
      row["not_computed"] = e.what();
    }
    rows.push_back(row);
  }
  return rows;
}

int cmd_wellposed(const WellposedOptions& opt) {
  Scene scene = Scene::load(opt.scene, opt.scene_text);
  for (const auto& a : opt.sets) scene.set(a);
  const Simulation sim = make_simulation(scene);
  const WellPosednessSetup setup = wellposedness_setup(sim);
  if (!opt.json)
    std::printf("condition (12) on %s (%d vertices, %d constraints)\n%-14s %7s %7s %9s %6s %12s  %s\n",
                sim.scene_name.c_str(), sim.mesh->n_vertices(), static_cast<int>(setup.constrained_vertices.size()),
                "pair", "N_W", "N_H", "dimKerB", "N_g", "beta", "satisfied");
  const nlohmann::ordered_json rows = wellposed_rows(sim);
  if (opt.json) {
    std::cout << rows.dump(2) << "\n";
    return 0;
  }
  for (const auto& row : rows) {
    const std::string pair = row["pair"];
    if (row.contains("not_computed"))
      std::printf("%-14s  not computed: %s\n", pair.c_str(), row["not_computed"].get<std::string>().c_str());
    else
      std::printf("%-14s %7d %7d %9d %6d %12.4e  %s\n", pair.c_str(), row["N_W"].get<int>(), row["N_H"].get<int>(),
                  row["dim_ker_B"].get<int>(), row["N_g"].get<int>(), row["beta"].get<double>(),
                  row["satisfied"].get<bool>() ? "yes" : "no");
  }
  return 0;
}

}  // namespace cdyn::app
