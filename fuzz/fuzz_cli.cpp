// libFuzzer harness: the luxel command line (apps/luxel/command_line.cpp), parsed and checked
// in-process as main() does before any work: CLI11's parsing and validators, --size, --eye,
// --target, --up, --sun, --mode, --tonemap, the solver, backend and --set options. Nothing is
// loaded, solved or written: runCommand is not called, and the outputs' check (which looks at the
// file system) belongs to the commands.
//
// The input is the argument words after "luxel", separated by NUL or newline bytes. A
// CLI::ParseError (bad usage, --help, --version) or a luxel::Error is the answer to a bad command
// line; anything else escaping is a bug to fix.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_line.h"
#include "luxel/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> words{"luxel"};
  std::string word;
  for (size_t i = 0; i < size; ++i) {
    const char c = char(data[i]);
    if (c == '\0' || c == '\n') {
      words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (size > 0) words.push_back(word);
  std::vector<const char*> argv;
  for (const std::string& w : words) argv.push_back(w.c_str());
  argv.push_back(nullptr);

  // A fresh app each time: CLI11 keeps what it parsed.
  const auto line = luxel::cli::makeCommandLine();
  try {
    luxel::cli::parseCommandLine(*line, int(words.size()), argv.data());
  } catch (const CLI::ParseError&) {
  } catch (const luxel::Error&) {
  }
  return 0;
}
