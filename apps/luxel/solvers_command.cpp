#include "solvers_command.h"

#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "luxel/solver.h"

namespace luxel::cli {

int listSolvers(bool json) {
  const std::vector<SolverDescription> solvers = registeredSolvers();
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const SolverDescription& s : solvers) {
      nlohmann::json options = nlohmann::json::array();
      for (const SolverOption& o : s.options)
        options.push_back({{"name", o.name}, {"default", o.defaultValue}, {"help", o.help}});
      out.push_back({{"name", s.name}, {"backend", s.backend}, {"description", s.description}, {"options", options}});
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  for (const SolverDescription& s : solvers) {
    std::cout << fmt::format("{} --backend {}\n  {}\n", s.name, s.backend, s.description);
    for (const SolverOption& o : s.options)
      std::cout << fmt::format("  --set {:<28} {} (default {})\n", o.name + "=...", o.help, o.defaultValue);
    std::cout << "\n";
  }
  std::cout << "Set any option with --set NAME=VALUE; one the chosen solver does not read is an error.\n";
  return 0;
}

}  // namespace luxel::cli
