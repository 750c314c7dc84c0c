// Atomic output: write a temporary file beside the target, then rename it over the target, so a
// failed or interrupted write never leaves a half-written file under the final name.
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string_view>

namespace luxel {

// Calls `write` with a fresh temporary path in the same directory as `path` (same directory so the
// rename stays on one file system and is atomic), then renames the temporary file to `path`.
// `write` reports failure by throwing; any std::exception it throws is rethrown as
// luxel::Error("<path>: <what>") after the temporary file is removed (Cancelled passes through
// unchanged). The parent directory must exist: it is never created.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& write);

// Removes the temporary files writeFileAtomically is writing right now. Async-signal-safe (it only
// reads lock-free atomics and calls unlink), for a SIGTERM or second-SIGINT handler that is about
// to end the process, so that no hidden partial file is left behind.
void removeTemporaryFilesNow() noexcept;

// A file opened for writing whose every write, and whose close, is checked: a full disk or a file
// size limit throws Error with the system's reason instead of leaving a short file that looks
// complete. For use inside writeFileAtomically's `write`.
class OutputFile {
 public:
  explicit OutputFile(const std::filesystem::path& path);
  ~OutputFile();  // closes without checking: a file not close()d was being abandoned anyway
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(const void* data, size_t bytes);
  void write(std::string_view text) { write(text.data(), text.size()); }
  void close();  // flushes; throws when anything written did not reach the file

 private:
  std::FILE* file_ = nullptr;
};

// writeFileAtomically with one OutputFile holding `text`.
void writeTextAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace luxel
