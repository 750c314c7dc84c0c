// SolverSettings (luxel/solver.h): names and values as text, until a solver reads them.
#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/solver.h"

namespace luxel {

SolverSettings& SolverSettings::set(const std::string& name, std::string value) {
  if (name.empty()) throw Error("solver option: empty name");
  values_[name] = std::move(value);
  return *this;
}

SolverSettings& SolverSettings::set(const std::string& name, double value) {
  return set(name, fmt::format("{}", value));  // shortest text that reads back as the same double
}

SolverSettings& SolverSettings::parse(std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw Error(fmt::format("--set '{}': expected NAME=VALUE", assignment));
  return set(std::string(assignment.substr(0, eq)), std::string(assignment.substr(eq + 1)));
}

const std::string* SolverSettings::find(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? nullptr : &it->second;
}

}  // namespace luxel
