// A solver's options, parsed and checked against what it declares (SolverOption) before it sees
// them: an undeclared name, a value of the wrong kind or out of range is an Error that names the
// solver and lists what it reads.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "luxel/solver.h"

namespace luxel {

class SolverOptionValues {
 public:
  // `solver` names the solver in messages, e.g. "progressive on cpu".
  SolverOptionValues(std::string solver, const std::vector<SolverOption>& declared, const SolverSettings& settings);

  double real(const std::string& name) const;
  int integer(const std::string& name) const;
  bool flag(const std::string& name) const;
  const std::string& choice(const std::string& name) const;
  bool declares(const std::string& name) const { return values_.count(name) != 0; }
  // A value the solver found wrong in combination with others; throws Error naming the solver.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  struct Value {
    SolverOption::Kind kind;
    std::string text;
    double number = 0.0;
    bool on = false;
  };
  const Value& at(const std::string& name, SolverOption::Kind kind) const;
  std::string solver_;
  std::map<std::string, Value> values_;
};

// The names of `declared`, for messages: "a, b, c" or "none".
std::string optionNames(const std::vector<SolverOption>& declared);

// Option declarations, shorter to write.
SolverOption realOption(std::string name, double value, double min, double max, std::string help);
SolverOption integerOption(std::string name, int value, int min, int max, std::string help);
SolverOption flagOption(std::string name, bool value, std::string help);
SolverOption choiceOption(std::string name, std::string value, std::vector<std::string> choices, std::string help);

}  // namespace luxel
