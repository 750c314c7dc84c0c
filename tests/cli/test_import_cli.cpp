// What `luxel render` says about scene paths and files that would otherwise fail quietly (issue
// 18): a FIFO given as the scene (opening it would wait for a writer forever), and an OBJ whose
// material library is missing (its light is gone: a black image with exit 0).
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "cli/cli_runner.h"

namespace {

TEST(ImportCli, AFifoAsTheSceneFailsAtOnceSayingWhatItIs) {
  const fs::path dir = scratchDir();
  ASSERT_EQ(mkfifo((dir / "pipe.json").c_str(), 0600), 0);
  const CliRun r = luxel(dir, args({"render", "pipe.json", "-o", "out.png"}));
  expectFailure(r, dir, {"pipe.json"}, {"pipe.json: is not a regular file (a FIFO, socket or device)"});
}

TEST(ImportCli, AMissingMaterialLibraryIsPrintedAsAWarning) {
  const fs::path dir = scratchDir();
  writeFile(dir / "room.obj", "mtllib lamp.mtl\nusemtl light\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const CliRun r = luxel(dir, args({"render", "room.obj", "-o", "out.png"}, {"--size", "8x8", "--elements", "200"}));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("luxel: warning: room.obj: line 1: material library 'lamp.mtl' not found"), std::string::npos)
      << r.err;
}

}  // namespace
