// The luxel command line: its options, and parsing and checking them without touching a file,
// loading a scene or solving. main() runs what this returns; fuzz/fuzz_cli.cpp parses in-process.
#pragma once

#include <memory>

#include <CLI/CLI.hpp>

#include "animate_command.h"
#include "bake_command.h"
#include "bench_command.h"
#include "render_command.h"
#include "view_command.h"

namespace luxel::cli {

struct CommandLine {
  CLI::App app{"luxel: radiosity global illumination"};
  RenderArgs render;
  AnimateArgs animate;
  BakeArgs bake;
  BenchArgs bench;
  ViewerArgs view;
  bool solversJson = false;
  CLI::App* renderCommand = nullptr;
  CLI::App* animateCommand = nullptr;
  CLI::App* bakeCommand = nullptr;
  CLI::App* benchCommand = nullptr;
  CLI::App* solversCommand = nullptr;
  CLI::App* viewCommand = nullptr;
};

// The app with every subcommand and option, bound to the returned object's arguments (which is
// why it is not copied or moved).
std::unique_ptr<CommandLine> makeCommandLine();

// Parses argv (argv[0] is the program) and checks the chosen command's arguments: sizes, vectors,
// modes, the solver and its options. Throws CLI::ParseError (bad usage, or --help / --version) or
// Error; writes nothing and reads no file. The outputs are checked by the command, before its work.
void parseCommandLine(CommandLine& line, int argc, const char* const* argv);

// Runs the parsed command; returns its exit code. Throws what the command throws.
int runCommand(const CommandLine& line);

}  // namespace luxel::cli
