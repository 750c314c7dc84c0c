// The options every command that solves a scene shares (render, bake): discretisation, solver,
// backend. One definition, so the commands cannot drift apart.
#pragma once

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

#include "luxel/solve.h"
#include "luxel/surface.h"

namespace luxel::cli {

struct SolveArgs {
  std::string solver = "progressive";
  std::string backend = "cpu";
  size_t elements = 0;
  float elementSize = 0.0f;
  double unshot = 1e-3;
  size_t refine = 0;
  int raysPerPair = 0;
  int hemicubeResolution = 0;  // 0: the method's default
  int hemicubesPerSide = 0;
  int emitterHemicubesPerSide = -1;  // -1: the solver's default
  int shootersPerPass = 0;  // 0: the solver's choice
  std::string hemicubeVisibility = "item";
};

// Adds --solver, --backend, --elements / --element-size, --unshot, --refine, --rays-per-pair, and
// the GL backend's --hemicube-resolution, --hemicubes-per-side, --hemicube-visibility.
void addSolveOptions(CLI::App& command, SolveArgs& args);

DiscretiseOptions discretiseOptions(const SolveArgs& args);
SolveOptions solveOptions(const SolveArgs& args);  // throws Error on an unknown solver or backend

}  // namespace luxel::cli
