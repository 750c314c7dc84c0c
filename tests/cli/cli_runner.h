// Running the luxel command-line tool as a separate process, for the CLI tests.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

// A fresh folder for the current test under LUXEL_TEST_TMP/cli.
fs::path scratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "cli" / (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeFile(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct CliRun {
  int code = -1;
  std::string out, err;
};

// Runs `luxel ARGS` in `dir` (the working directory), capturing stdout, stderr and the exit code.
CliRun luxel(const fs::path& dir, const std::vector<std::string>& args) {
  std::string cmd = "cd " + quote(dir.string()) + " && " + quote(LUXEL_CLI);
  for (const std::string& a : args) cmd += " " + quote(a);
  const fs::path outFile = dir.parent_path() / (dir.filename().string() + ".stdout");
  const fs::path errFile = dir.parent_path() / (dir.filename().string() + ".stderr");
  cmd += " >" + quote(outFile.string()) + " 2>" + quote(errFile.string()) + " </dev/null";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readFile(outFile);
  r.err = readFile(errFile);
  return r;
}

}  // namespace
