// The luxel command-line tool. Thin: parse options (command_line.cpp), run the command, print one
// summary or one error. Exit codes: 0 success, 1 error, 2 bad usage, 130 cancelled (Ctrl-C).
#include <iostream>
#include <new>

#include <CLI/CLI.hpp>

#include "luxel/error.h"
#include "command_line.h"
#include "out_of_memory.h"

int main(int argc, char** argv) {
  using namespace luxel;
  const std::unique_ptr<cli::CommandLine> line = cli::makeCommandLine();
  try {
    try {
      cli::parseCommandLine(*line, argc, argv);
    } catch (const CLI::ParseError& e) {
      return line->app.exit(e) == 0 ? 0 : 2;
    }
    return cli::runCommand(*line);
  } catch (const Cancelled&) {
    std::cerr << "\nluxel: cancelled\n";
    return 130;
  } catch (const std::bad_alloc&) {
    // Here, once, for every command: they say what they are doing as they go (out_of_memory.h).
    std::cerr << "\nluxel: error: " << cli::outOfMemoryMessage() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "\nluxel: error: " << e.what() << "\n";
    return 1;
  }
}
