// `luxel bench [SUITE] [--runs N] [--json FILE]`: runs a benchmark suite, prints a table and
// writes the results with the machine, commit and date as JSON.
#pragma once

#include <string>

namespace luxel::cli {

struct BenchArgs {
  std::string suite = "seeds";
  int runs = 5;
  std::string jsonPath;
  std::string filter;  // only cases whose name contains this
  std::string cacheDir;
  bool noReference = false;
  std::string reference = "cpu";  // cpu or monte-carlo
  bool noLimit = false;
  bool list = false;
  int threads = 0;
  bool quiet = false;
};

int runBench(const BenchArgs& args);

}  // namespace luxel::cli
