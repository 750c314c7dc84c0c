// `luxel bench [SUITE] [--runs N] [--json FILE]`: runs a benchmark suite, prints a table and
// writes the results with the machine, commit and date as JSON. `luxel bench dynamic [--frames N]`
// runs seed 001's moving box frame by frame instead (bench.h, runDynamicCase).
#pragma once

#include <string>
#include <vector>

namespace luxel::cli {

struct BenchArgs {
  std::string suite = "seeds";
  int runs = 5;
  std::string jsonPath;
  std::string filter;  // only cases whose name contains this
  // Solver options NAME=VALUE laid over each case's own (not the references'); an option the
  // case's solver does not read is an error, as with render's --set.
  std::vector<std::string> set;
  std::string cacheDir;
  bool noReference = false;
  std::string reference = "cpu";  // cpu or monte-carlo
  bool noLimit = false;
  bool list = false;
  int threads = 0;
  bool quiet = false;
  // The dynamic suite's own options (an error with any other suite): moving frames per case, GL
  // cases' frames (0: all on a GPU, none on a software rasteriser), and which scenes and backends
  // run (empty: all).
  int frames = 100;
  int glFrames = 0;
  std::vector<std::string> scenes;
  std::vector<std::string> backends;
  bool runsGiven = false, dynamicOptionGiven = false;  // set by parseCommandLine
};

// Checks the suite-specific options: --runs with the dynamic suite, or its options with another.
void checkBenchArgs(const BenchArgs& args);

int runBench(const BenchArgs& args);

}  // namespace luxel::cli
