// Checkpoints (issue 18): a finished solve resumes as finished; a checkpoint of another solve, or
// a damaged one, is an Error that says which. That every solver that can be checkpointed resumes
// to the bits of an uninterrupted solve is checked for each by the conformance suite.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/session.h"
#include "luxel/import.h"
#include "error_message.h"

namespace luxel {
namespace {

using luxel::test::errorOf;

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(LUXEL_TEST_TMP) / "checkpoint";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

SessionOptions options(const std::string& method, const CheckpointOptions& checkpoint = {}) {
  SessionOptions o;
  o.solve.method = method;
  o.solve.checkpoint = checkpoint;
  // Long enough that a few steps are part of it: gathering converges in tens of sweeps, progressive
  // in hundreds of shots, the hierarchy in a dozen sweeps.
  if (method == "progressive") o.solve.settings.set("unshot", 1e-5).set("shooters-per-pass", 4);
  if (method == "hierarchical") o.solve.settings.set("unshot", 1e-5).set("cache", false);
  return o;
}

DiscretiseOptions small() {
  DiscretiseOptions d;
  d.elementBudget = 1500;
  return d;
}

bool bitIdentical(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)) == 0;
}

TEST(Checkpoint, AFinishedSolveResumesAsFinished) {
  const Scene scene = builtinScene("cornell");
  const fs::path file = scratch("finished.ckpt");
  Session first(scene, small(), options("progressive", {.path = file}));
  const Solution expected = first.solve();  // the checkpoint is written at the end
  Session again(scene, small(), options("progressive", {.resume = file}));
  EXPECT_FALSE(again.step({.units = 1}));
  EXPECT_TRUE(bitIdentical(expected.radiosity, again.solution().radiosity));
}

TEST(Checkpoint, AnotherSolvesOrADamagedCheckpointIsRefused) {
  const Scene scene = builtinScene("cornell");
  const fs::path file = scratch("other.ckpt");
  {
    Session first(scene, small(), options("progressive", {.path = file, .intervalSeconds = 1e-9}));
    first.step({.units = 1});
  }
  // Other elements, another solver, another option: each another solve.
  DiscretiseOptions finer = small();
  finer.elementBudget = 2000;
  EXPECT_NE(errorOf([&] { Session s(scene, finer, options("progressive", {.resume = file})); }).find("another solve"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { Session s(scene, small(), options("gather", {.resume = file})); }).find("another solve"),
            std::string::npos);
  SessionOptions tighter = options("progressive", {.resume = file});
  tighter.solve.settings.set("unshot", 1e-6);
  EXPECT_NE(errorOf([&] { Session s(scene, small(), tighter); }).find("another solve"), std::string::npos);

  // Cut short, or one byte changed: damaged.
  const auto size = fs::file_size(file);
  const fs::path cut = scratch("cut.ckpt"), flipped = scratch("flipped.ckpt");
  fs::copy_file(file, cut);
  fs::resize_file(cut, size - 7);
  EXPECT_NE(errorOf([&] { Session s(scene, small(), options("progressive", {.resume = cut})); }).find("damaged"),
            std::string::npos);
  fs::copy_file(file, flipped);
  {
    std::fstream f(flipped, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(size - 100));
    f.put('\x5a');
  }
  EXPECT_NE(errorOf([&] { Session s(scene, small(), options("progressive", {.resume = flipped})); }).find("checksum"),
            std::string::npos);
  const fs::path text = scratch("text.ckpt");
  std::ofstream(text) << "not a checkpoint";
  EXPECT_NE(errorOf([&] { Session s(scene, small(), options("progressive", {.resume = text})); })
                .find("not a luxel checkpoint"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { Session s(scene, small(), options("progressive", {.resume = scratch("none.ckpt")})); })
                .find("no such file"),
            std::string::npos);
}

TEST(Checkpoint, RefinementIsRefusedRatherThanResumedWrong) {
  const Scene scene = builtinScene("cornell");
  SessionOptions o = options("progressive", {.path = scratch("refine.ckpt")});
  o.solve.refine.budget = 100;
  EXPECT_NE(errorOf([&] { Session s(scene, small(), o); }).find("--refine"), std::string::npos);
}

}  // namespace
}  // namespace luxel
