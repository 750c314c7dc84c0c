// Importing a model in a child process, so that whatever the importer does with a hostile file
// becomes an Error naming the file, never a crash of the caller.
//
// Why: Debian's Assimp crashes, loops and allocates without bound on malformed files (what fuzzing
// found, and how soon: docs/hostile-inputs.md),
// and a crash in-process takes the whole run with it. Checks before Assimp (PLY and GLB headers)
// close the holes found so far, not the ones not found yet. Browsers isolate their parsers of
// untrusted files the same way.
//
// How: the child, forked with limits on its address space and time, runs the import (Assimp and
// luxel's conversion of its scene, textures decoded) and writes the Scene as bytes
// (scene/scene_bytes.h) to a memory file, which the parent reads back once the child has exited.
// A child that crashes, runs past its time or memory, or ends without a scene is an Error saying
// which. The child is a fork: the ResourceReader it calls is a copy, whose side effects stay in
// the child.
//
// LUXEL_IMPORT_IN_PROCESS=1 in the environment (for a debugger), or the fuzzing build (whose
// coverage must see the importer), imports in-process instead.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "luxel/scene.h"

namespace luxel {

struct ChildProcessLimits {
  double seconds = 0.0;  // 0: 60 s plus 2 s per MB of the input
  size_t bytes = 0;      // more address space than the parent's; 0: 3/4 of the machine's memory, at least 4 GiB
};

// Runs `import` in a child process (in-process when isolation is off) and returns its scene.
// `file` names the model in messages; `inputBytes` sizes the default time limit.
Scene importInChildProcess(const std::string& file, size_t inputBytes, const std::function<Scene()>& import,
                           ChildProcessLimits limits = {});

}  // namespace luxel
