#include "scene/import/child_process_import.h"

#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "luxel/error.h"
#include "scene/scene_bytes.h"

namespace luxel {
namespace {

bool inProcess() {
#ifdef LUXEL_IMPORT_IN_PROCESS
  return true;
#else
  const char* v = std::getenv("LUXEL_IMPORT_IN_PROCESS");
  return v && *v && std::strcmp(v, "0") != 0;
#endif
}

// AddressSanitizer reserves terabytes of address space for its shadow memory, so a limit on the
// address space would stop it from starting anything: under it, the child runs without one.
constexpr bool kAddressSanitizer =
#if defined(__SANITIZE_ADDRESS__)
    true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    true;
#else
    false;
#endif
#else
    false;
#endif

size_t defaultMemoryBudget() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  const size_t physical = pages > 0 && page > 0 ? size_t(pages) * size_t(page) : 0;
  return std::max(size_t(4) << 30, physical / 4 * 3);
}

// The child's address space so far (inherited from the parent): the limit is set above it.
size_t addressSpaceInUse() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0;
  statm >> pages;
  return pages * size_t(sysconf(_SC_PAGE_SIZE));
}

// The child's exit status when it could not write its result.
constexpr int kChildWriteFailed = 3;

bool writeAll(int fd, const void* data, size_t size) {
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n, size -= size_t(n);
  }
  return true;
}

// The child: limits, the import, and its result into `fd` as 'S' and the scene's bytes, or 'E'
// and the message. Never returns; exits without running the parent's exit handlers.
[[noreturn]] void importInChild(int fd, size_t memoryBudget, const std::string& file, const std::function<Scene()>& import) {
  // Ctrl-C and SIGTERM end the child (the parent's handlers, inherited, would only set a flag),
  // and so does the death of the parent's thread that waits for it.
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  const rlimit noCore{0, 0};
  setrlimit(RLIMIT_CORE, &noCore);  // a crash is reported by the parent, not dumped
  if (!kAddressSanitizer) {
    const rlimit memory{addressSpaceInUse() + memoryBudget, RLIM_INFINITY};
    setrlimit(RLIMIT_AS, &memory);
  }
  std::string message;
  try {
    const std::vector<std::byte> bytes = sceneBytes(import());
    _exit(writeAll(fd, "S", 1) && writeAll(fd, bytes.data(), bytes.size()) ? 0 : kChildWriteFailed);
  } catch (const std::bad_alloc&) {
    message = fmt::format("{}: ran out of memory importing it: the file is malformed, or too big to import", file);
  } catch (const std::exception& e) {
    message = e.what();
    if (message.find("bad_alloc") != std::string::npos)  // Assimp's importers catch it and keep its name
      message = fmt::format("{}: ran out of memory importing it: the file is malformed, or too big to import", file);
  }
  message.insert(0, "E");
  _exit(writeAll(fd, message.data(), message.size()) ? 0 : kChildWriteFailed);
}

std::string signalName(int signal) {
  switch (signal) {
    case SIGSEGV: return "a segmentation fault";
    case SIGBUS: return "a bus error";
    case SIGFPE: return "an arithmetic exception";
    case SIGILL: return "an illegal instruction";
    case SIGABRT: return "an abort";
    case SIGKILL: return "SIGKILL, most likely the system running out of memory";
    default: return fmt::format("signal {} ({})", signal, strsignal(signal));
  }
}

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

Scene importInChildProcess(const std::string& file, size_t inputBytes, const std::function<Scene()>& import,
                           ChildProcessLimits limits) {
  if (inProcess()) return import();
  const double seconds = limits.seconds > 0.0 ? limits.seconds : 60.0 + 2.0 * double(inputBytes) / 1e6;
  const size_t memory = limits.bytes > 0 ? limits.bytes : defaultMemoryBudget();

  const FileDescriptor result(memfd_create("luxel-import", MFD_CLOEXEC));
  if (result.get() < 0) throw Error(fmt::format("{}: cannot make the importer's result file: {}", file, std::strerror(errno)));
  const pid_t child = fork();
  if (child < 0) throw Error(fmt::format("{}: cannot start the importer's process: {}", file, std::strerror(errno)));
  if (child == 0) importInChild(result.get(), memory, file, import);

  // Waits, polling ever less often up to 20 ms: most files take milliseconds.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  auto pause = std::chrono::microseconds(100);
  int status = 0;
  while (true) {
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0 && errno != EINTR) throw Error(fmt::format("{}: lost the importer's process: {}", file, std::strerror(errno)));
    if (std::chrono::steady_clock::now() > deadline) {
      kill(child, SIGKILL);
      while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
      }
      throw Error(fmt::format("{}: the importer was still reading it after {:.3g} s and was stopped: the file is "
                              "malformed, or too big to import",
                              file, seconds));
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20000));
  }
  if (WIFSIGNALED(status)) {
    if (WTERMSIG(status) == SIGINT) throw Cancelled();
    throw Error(fmt::format("{}: the importer crashed reading it, with {}: the file is malformed", file,
                            signalName(WTERMSIG(status))));
  }
  // The child itself exits 0, or kChildWriteFailed; any other status is something ending it on its
  // way, such as a sanitizer's report of a crash.
  if (WIFEXITED(status) && WEXITSTATUS(status) == kChildWriteFailed)
    throw Error(fmt::format("{}: the importer could not hand its result over (out of memory for it?)", file));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(fmt::format("{}: the importer crashed reading it (it ended with exit status {}): the file is malformed",
                            file, WIFEXITED(status) ? WEXITSTATUS(status) : -1));

  struct stat info {};
  if (fstat(result.get(), &info) != 0 || info.st_size < 1)
    throw Error(fmt::format("{}: the importer ended without a result", file));
  std::vector<std::byte> out(size_t(info.st_size));
  size_t got = 0;
  while (got < out.size()) {
    const ssize_t n = pread(result.get(), out.data() + got, out.size() - got, off_t(got));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(fmt::format("{}: cannot read the importer's result: {}", file, std::strerror(errno)));
    got += size_t(n);
  }
  if (out[0] == std::byte{'E'}) throw Error(std::string(reinterpret_cast<const char*>(out.data()) + 1, out.size() - 1));
  if (out[0] != std::byte{'S'}) throw Error(fmt::format("{}: the importer's result is garbled", file));
  return sceneFromBytes(std::span<const std::byte>(out).subspan(1));
}

}  // namespace luxel
