#include "solve/solver_options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"

namespace luxel {
namespace {

const char* kindName(SolverOption::Kind k) {
  switch (k) {
    case SolverOption::Kind::Real: return "a number";
    case SolverOption::Kind::Integer: return "a whole number";
    case SolverOption::Kind::Flag: return "true or false";
    case SolverOption::Kind::Choice: return "a choice";
  }
  return "?";
}

bool parseNumber(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno == 0 && std::isfinite(out);
}

bool parseFlag(const std::string& text, bool& out) {
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (t == "true" || t == "1" || t == "on" || t == "yes") return out = true, true;
  if (t == "false" || t == "0" || t == "off" || t == "no") return out = false, true;
  return false;
}

}  // namespace

std::string optionNames(const std::vector<SolverOption>& declared) {
  std::vector<std::string> names;
  for (const SolverOption& o : declared) names.push_back(o.name);
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

SolverOptionValues::SolverOptionValues(std::string solver, const std::vector<SolverOption>& declared,
                                       const SolverSettings& settings)
    : solver_(std::move(solver)) {
  for (const auto& entry : settings.values()) {
    const std::string& name = entry.first;  // a structured binding cannot be captured before clang 16 (make fuzz)
    auto it = std::find_if(declared.begin(), declared.end(), [&](const SolverOption& o) { return o.name == name; });
    if (it == declared.end())
      throw Error(fmt::format("{} has no option '{}' (its options: {})", solver_, name, optionNames(declared)));
  }
  for (const SolverOption& o : declared) {
    const std::string* given = settings.find(o.name);
    Value v{o.kind, given ? *given : o.defaultValue};
    auto bad = [&](const std::string& why) {
      throw Error(fmt::format("{}: option {}={}: {}", solver_, o.name, v.text, why));
    };
    switch (o.kind) {
      case SolverOption::Kind::Real:
      case SolverOption::Kind::Integer:
        if (!parseNumber(v.text, v.number)) bad(fmt::format("expected {}", kindName(o.kind)));
        if (o.kind == SolverOption::Kind::Integer && v.number != std::floor(v.number))
          bad("expected a whole number");
        if (v.number < o.min || v.number > o.max) bad(fmt::format("must be in {}..{}", o.min, o.max));
        break;
      case SolverOption::Kind::Flag:
        if (!parseFlag(v.text, v.on)) bad("expected true or false");
        break;
      case SolverOption::Kind::Choice:
        if (std::find(o.choices.begin(), o.choices.end(), v.text) == o.choices.end())
          bad(fmt::format("expected one of {}", fmt::join(o.choices, ", ")));
        break;
    }
    values_.emplace(o.name, std::move(v));
  }
}

const SolverOptionValues::Value& SolverOptionValues::at(const std::string& name, SolverOption::Kind kind) const {
  auto it = values_.find(name);
  // A solver reading an option it did not declare, or as another kind, is a bug in the solver.
  if (it == values_.end()) throw Error(fmt::format("{} reads option '{}' without declaring it", solver_, name));
  if (it->second.kind != kind)
    throw Error(fmt::format("{} reads option '{}' as {}, declared as {}", solver_, name, kindName(kind),
                            kindName(it->second.kind)));
  return it->second;
}

double SolverOptionValues::real(const std::string& name) const { return at(name, SolverOption::Kind::Real).number; }
int SolverOptionValues::integer(const std::string& name) const {
  return int(at(name, SolverOption::Kind::Integer).number);
}
bool SolverOptionValues::flag(const std::string& name) const { return at(name, SolverOption::Kind::Flag).on; }
const std::string& SolverOptionValues::choice(const std::string& name) const {
  return at(name, SolverOption::Kind::Choice).text;
}

void SolverOptionValues::fail(const std::string& what) const { throw Error(fmt::format("{}: {}", solver_, what)); }

SolverOption realOption(std::string name, double value, double min, double max, std::string help) {
  return {std::move(name), SolverOption::Kind::Real, fmt::format("{}", value), std::move(help), min, max, {}};
}
SolverOption integerOption(std::string name, int value, int min, int max, std::string help) {
  return {std::move(name), SolverOption::Kind::Integer, std::to_string(value), std::move(help), double(min), double(max), {}};
}
SolverOption flagOption(std::string name, bool value, std::string help) {
  return {std::move(name), SolverOption::Kind::Flag, value ? "true" : "false", std::move(help), 0, 0, {}};
}
SolverOption choiceOption(std::string name, std::string value, std::vector<std::string> choices, std::string help) {
  return {std::move(name), SolverOption::Kind::Choice, std::move(value), std::move(help), 0, 0, std::move(choices)};
}

}  // namespace luxel
