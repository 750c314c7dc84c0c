// Write-then-rename, the POSIX idiom for replacing a file atomically: rename(2) either installs
// the complete new file or leaves the old one untouched.
#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;

// Unique per process (counter) and across processes (pid), so concurrent writers of the same
// target never share a temporary file. The leading dot keeps it out of casual listings.
fs::path temporaryPathFor(const fs::path& path) {
  static std::atomic<unsigned long> counter{0};
  std::string name = fmt::format(".{}.tmp-{}-{}", path.filename().string(),
                                 static_cast<long>(::getpid()), counter.fetch_add(1));
  return path.parent_path() / name;
}

void removeQuietly(const fs::path& tmp) {
  std::error_code ignored;
  fs::remove(tmp, ignored);
}

// The temporary files being written, for removeTemporaryFilesNow. A signal handler can only read
// them through lock-free atomics, so the paths live in fixed slots: a slot is claimed (`claimed`),
// filled, then published (`path` set); a handler unlinks every published path.
constexpr size_t kSlots = 32;
constexpr size_t kSlotBytes = 4096;
struct TemporarySlot {
  std::atomic<bool> claimed{false};
  std::atomic<const char*> path{nullptr};
  char bytes[kSlotBytes];
};
TemporarySlot gTemporaries[kSlots];
static_assert(std::atomic<const char*>::is_always_lock_free);

// Publishes a temporary path while it lives; a path too long for a slot, or a 33rd concurrent
// writer, is simply not published (only a signal during its write would leave it behind).
class PublishedTemporary {
 public:
  explicit PublishedTemporary(const fs::path& tmp) {
    const std::string& text = tmp.native();
    if (text.size() >= kSlotBytes) return;
    for (TemporarySlot& slot : gTemporaries) {
      bool expected = false;
      if (!slot.claimed.compare_exchange_strong(expected, true)) continue;
      std::memcpy(slot.bytes, text.c_str(), text.size() + 1);
      slot.path.store(slot.bytes);
      slot_ = &slot;
      return;
    }
  }
  ~PublishedTemporary() {
    if (!slot_) return;
    slot_->path.store(nullptr);
    slot_->claimed.store(false);
  }
  PublishedTemporary(const PublishedTemporary&) = delete;
  PublishedTemporary& operator=(const PublishedTemporary&) = delete;

 private:
  TemporarySlot* slot_ = nullptr;
};

}  // namespace

void writeFileAtomically(const fs::path& path,
                         const std::function<void(const fs::path& tmp)>& write) {
  if (path.filename().empty()) {
    throw Error(fmt::format("{}: not a file name", path.string()));
  }
  // An empty parent means the current directory.
  fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw Error(fmt::format("{}: directory '{}' does not exist", path.string(), dir.string()));
  }

  fs::path tmp = temporaryPathFor(path);
  const PublishedTemporary published(tmp);
  try {
    write(tmp);
  } catch (const Cancelled&) {
    removeQuietly(tmp);
    throw;
  } catch (const std::exception& e) {
    removeQuietly(tmp);
    throw Error(fmt::format("{}: {}", path.string(), e.what()));
  } catch (...) {
    removeQuietly(tmp);
    throw Error(fmt::format("{}: write failed", path.string()));
  }

  if (!fs::is_regular_file(tmp, ec)) {
    removeQuietly(tmp);
    throw Error(fmt::format("{}: the writer produced no file", path.string()));
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    removeQuietly(tmp);
    throw Error(fmt::format("{}: cannot rename temporary file into place: {}", path.string(),
                            ec.message()));
  }
}

void removeTemporaryFilesNow() noexcept {
  for (TemporarySlot& slot : gTemporaries)
    if (const char* p = slot.path.load()) ::unlink(p);
}

OutputFile::OutputFile(const fs::path& path) {
  errno = 0;
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw Error(fmt::format("cannot open for writing: {}", std::strerror(errno)));
}

OutputFile::~OutputFile() {
  if (file_) std::fclose(file_);
}

void OutputFile::write(const void* data, size_t bytes) {
  if (!file_) throw Error("write after close");
  errno = 0;
  if (bytes > 0 && std::fwrite(data, 1, bytes, file_) != bytes)
    throw Error(fmt::format("write failed: {}", errno ? std::strerror(errno) : "short write"));
}

void OutputFile::close() {
  if (!file_) return;
  errno = 0;
  const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
  const int flushError = errno;
  errno = 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed)
    throw Error(fmt::format("write failed: {}", std::strerror(flushError ? flushError : errno ? errno : EIO)));
}

void writeTextAtomically(const fs::path& path, std::string_view text) {
  writeFileAtomically(path, [&](const fs::path& tmp) {
    OutputFile out(tmp);
    out.write(text);
    out.close();
  });
}

}  // namespace luxel
