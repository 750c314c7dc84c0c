// Atomic output: write a temporary file beside the target, then rename it over the target, so a
// failed or interrupted write never leaves a half-written file under the final name.
#pragma once

#include <filesystem>
#include <functional>

namespace luxel {

// Calls `write` with a fresh temporary path in the same directory as `path` (same directory so the
// rename stays on one file system and is atomic), then renames the temporary file to `path`.
// `write` reports failure by throwing; any std::exception it throws is rethrown as
// luxel::Error("<path>: <what>") after the temporary file is removed (Cancelled passes through
// unchanged). The parent directory must exist: it is never created.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& write);

}  // namespace luxel
