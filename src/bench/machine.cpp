// Which machine and which build a benchmark result belongs to, and how much memory a run peaked
// at (Linux: the VmHWM high-water mark, reset between runs through /proc/self/clear_refs).
#include <malloc.h>
#include <sys/resource.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "bench/memory.h"
#include "luxel/bench.h"

namespace luxel::bench {
namespace {

std::string firstLineStartingWith(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return line;
  return {};
}

std::string trim(std::string s) {
  const char* ws = " \t\n\r";
  s.erase(0, s.find_first_not_of(ws));
  s.erase(s.find_last_not_of(ws) + 1);
  return s;
}

std::string run(const std::string& cmd) {
  std::array<char, 128> buf{};
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    while (fgets(buf.data(), int(buf.size()), p)) out += buf.data();
    pclose(p);
  }
  return trim(out);
}

// The commit of the tree the binary was built from, "-dirty" when its code (not its result
// files) has uncommitted changes. The source directory is compiled in; when it is gone (an
// installed binary), the commit is simply unknown.
std::string sourceCommit() {
#ifdef LUXEL_SOURCE_DIR
  const std::string git = fmt::format("git -C '{}' ", LUXEL_SOURCE_DIR);
  std::string commit = run(git + "rev-parse --short HEAD 2>/dev/null");
  if (!commit.empty() &&
      !run(git + "status --porcelain -- src include apps bench/*.cpp CMakeLists.txt 2>/dev/null").empty())
    commit += "-dirty";
  return commit;
#else
  return {};
#endif
}

}  // namespace

void resetPeakMemory() {
  // Hand freed heap back to the system first, or the previous case's memory would count as this
  // one's; then "5" resets the peak resident set size (Linux >= 4.0).
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
}

size_t peakMemoryBytes() {
  std::string line = firstLineStartingWith("/proc/self/status", "VmHWM:");
  if (!line.empty()) return size_t(std::stoull(line.substr(6))) * 1024;  // "VmHWM:  1234 kB"
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) return size_t(usage.ru_maxrss) * 1024;
  return 0;
}

Machine describeMachine(int threads) {
  Machine m;
  std::string model = firstLineStartingWith("/proc/cpuinfo", "model name");
  if (auto colon = model.find(':'); colon != std::string::npos) m.cpuModel = trim(model.substr(colon + 1));
  m.cores = int(sysconf(_SC_NPROCESSORS_ONLN));
  m.threads = threads;
  m.memoryBytes = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  utsname u{};
  if (uname(&u) == 0) m.os = fmt::format("{} {} {}", u.sysname, u.release, u.machine);
  m.commit = sourceCommit();
  std::time_t now = std::time(nullptr);
  std::array<char, 32> date{};
  std::strftime(date.data(), date.size(), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  m.date = date.data();
  return m;
}

}  // namespace luxel::bench
