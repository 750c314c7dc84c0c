// Write-then-rename, the POSIX idiom for replacing a file atomically: rename(2) either installs
// the complete new file or leaves the old one untouched.
#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
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

}  // namespace luxel
