// `luxel bench dynamic`: the dynamic suite's table and JSON (bench_dynamic.cpp), run by
// `luxel bench` (bench_command.cpp), which parses the arguments and describes the machine.
#pragma once

#include <nlohmann/json.hpp>

#include "bench_command.h"
#include "luxel/bench.h"

namespace luxel::cli {

// Runs the suite's cases that --scenes, --backends and --case leave, printing a row each (unless
// --quiet) and writing --json. Throws Error when no case matches or every one was skipped.
int runDynamicBench(const BenchArgs& args, const bench::Options& options, const bench::Machine& machine);
// `luxel bench --list`'s lines for the suite.
void listDynamicSuite();
// The machine as every suite's JSON gives it (bench_command.cpp).
nlohmann::json machineJson(const bench::Machine& machine);

}  // namespace luxel::cli
