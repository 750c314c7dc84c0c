// Running the luxel command-line tool as a separate process, for the CLI tests.
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <initializer_list>
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
// `shellSetup` runs first in the same shell (limits: "ulimit -f 8; "), and luxel is exec'd.
CliRun luxel(const fs::path& dir, const std::vector<std::string>& args, const std::string& shellSetup = "") {
  // "cd || exit" rather than "cd &&": a setup that ends in '&' would otherwise take the cd with it
  // into the background and leave luxel running in the test's own folder.
  std::string cmd = "cd " + quote(dir.string()) + " || exit 126; " + shellSetup + "exec " + quote(LUXEL_CLI);
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

inline std::vector<std::string> listDir(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) names.push_back(fs::relative(entry.path(), dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

inline std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += x + " ";
  return s;
}

inline void expectNoTemporaries(const fs::path& dir) {
  for (const std::string& name : listDir(dir)) EXPECT_EQ(name.find(".tmp"), std::string::npos) << "left behind: " << name;
}

// A failed run: exit code 1, an error on stderr containing every one of `parts`, and `dir` still
// holding exactly `before`.
inline void expectFailure(const CliRun& r, const fs::path& dir, const std::vector<std::string>& before,
                   std::initializer_list<std::string> parts, int code = 1) {
  EXPECT_EQ(r.code, code) << r.err;
  EXPECT_NE(r.err.find(code == 2 ? "" : "luxel: error:"), std::string::npos) << r.err;
  for (const std::string& p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << "'" << p << "' not in: " << r.err;
  EXPECT_EQ(listDir(dir), before) << "now: " << joined(listDir(dir));
  expectNoTemporaries(dir);
}

const std::vector<std::string> kQuick = {"--size", "8x8", "--elements", "200", "-q"};

inline std::vector<std::string> args(std::initializer_list<std::string> first, const std::vector<std::string>& rest = kQuick) {
  std::vector<std::string> a(first);
  a.insert(a.end(), rest.begin(), rest.end());
  return a;
}

}  // namespace
