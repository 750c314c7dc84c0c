// Terminal progress bar and log-friendly progress lines. The ETA is luxel::EtaEstimator's: a power
// of time fitted to the phase's recent reports, and none until there are enough.
#include "progress_bar.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "luxel/error.h"

namespace luxel::cli {
namespace {

// Only lock-free atomics may be touched from a signal handler.
std::atomic<bool> gInterrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);

// The first Ctrl-C asks the library to stop at its next progress report. A second one, or SIGTERM,
// ends the process at once, as the user expects, after removing the temporary file an output was
// being written to (the outputs themselves are only ever renamed into place complete).
extern "C" void onSigint(int signal) {
  if (!gInterrupted.exchange(true)) return;
  removeTemporaryFilesNow();
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

extern "C" void onSigterm(int signal) {
  removeTemporaryFilesNow();
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

constexpr int kBarWidth = 20;
constexpr double kTerminalInterval = 0.1;  // seconds between redraws: ~10 Hz, cheap and smooth
constexpr double kLogInterval = 2.0;       // seconds between lines in a log, per phase

std::string formatDuration(double seconds) {
  if (seconds < 60.0) return fmt::format("{:.1f}s", seconds);
  const long s = std::lround(seconds);
  if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}h{:02}m", s / 3600, (s % 3600) / 60);
}

// A fraction outside [0,1], or NaN, means the library does not know how far along it is.
bool isKnown(double fraction) { return fraction >= 0.0; }

int terminalColumns() {
  winsize size{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

// Cuts to at most `bytes` bytes without splitting a UTF-8 sequence.
void truncateUtf8(std::string& text, size_t bytes) {
  if (text.size() <= bytes) return;
  while (bytes > 0 && (static_cast<unsigned char>(text[bytes]) & 0xC0) == 0x80) --bytes;
  text.resize(bytes);
}

}  // namespace

ProgressBar::ProgressBar(bool quiet) : quiet_(quiet), terminal_(::isatty(STDERR_FILENO) == 1) {
  gInterrupted.store(false);
  struct sigaction action {};
  action.sa_handler = onSigint;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, &previousSigint_);
  action.sa_handler = onSigterm;
  ::sigaction(SIGTERM, &action, &previousSigterm_);
}

ProgressBar::~ProgressBar() {
  finish();
  ::sigaction(SIGINT, &previousSigint_, nullptr);
  ::sigaction(SIGTERM, &previousSigterm_, nullptr);
  try {
    writeTrace();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "luxel: error: %s\n", e.what());
  }
}

void ProgressBar::traceTo(const std::string& path) {
  const std::filesystem::path p(path);
  const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir))
    throw Error(fmt::format("--progress-trace {}: directory '{}' does not exist", path, dir.string()));
  tracePath_ = path;
}

void ProgressBar::writeTrace() {
  std::lock_guard lock(mutex_);
  if (tracePath_.empty()) return;
  const std::string path = std::exchange(tracePath_, {});
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    OutputFile out(tmp);
    for (const std::string& line : trace_) out.write(line);
    out.close();
  });
}

bool ProgressBar::interrupted() { return gInterrupted.load(); }

luxel::ProgressCallback ProgressBar::callback() {
  return [this](const luxel::ProgressEvent& event) { return update(event); };
}

bool ProgressBar::update(const luxel::ProgressEvent& event) {
  std::lock_guard lock(mutex_);
  if (!tracePath_.empty())
    trace_.push_back(fmt::format("{:.4f}\t{}\t{:.6f}\t{}\n",
                                 std::chrono::duration<double>(Clock::now() - created_).count(), event.phase,
                                 event.fraction, event.detail));
  if (interrupted()) {
    // End the bar so the CLI's "cancelled" message gets a line of its own.
    finishLocked();
    return false;
  }
  if (quiet_) return true;

  const Clock::time_point now = Clock::now();
  const bool newPhase = !havePhase_ || event.phase != phase_;
  if (newPhase) {
    finishLocked();
    phase_ = event.phase;
    havePhase_ = true;
    phaseDone_ = false;
    phaseStart_ = now;
    lastOutput_ = now;
    eta_ = luxel::EtaEstimator();
  }
  const bool done = event.fraction >= 1.0;
  if (done && phaseDone_) return true;  // show the end of a phase once
  const double elapsed = std::chrono::duration<double>(now - phaseStart_).count();
  const double sinceOutput = std::chrono::duration<double>(now - lastOutput_).count();
  if (isKnown(event.fraction)) eta_.add(elapsed, std::min(event.fraction, 1.0));

  if (terminal_) {
    if (newPhase || done || sinceOutput >= kTerminalInterval) {
      drawTerminal(event, elapsed, done);
      lastOutput_ = now;
    }
  } else if (done || sinceOutput >= kLogInterval) {
    printLogLine(event, elapsed, done);
    lastOutput_ = now;
  }
  phaseDone_ = phaseDone_ || done;
  return true;
}

void ProgressBar::finish() {
  std::lock_guard lock(mutex_);
  finishLocked();
}

void ProgressBar::finishLocked() {
  if (lineOpen_) std::fputc('\n', stderr);
  lineOpen_ = false;
}

// "solve [#########...........] 45% ETA 3.2s unshot 1.2%"
void ProgressBar::drawTerminal(const luxel::ProgressEvent& event, double elapsed, bool done) {
  std::string line;
  if (isKnown(event.fraction)) {
    const double f = std::min(event.fraction, 1.0);
    const int filled = int(f * kBarWidth);
    std::string time;
    if (done) {
      time = formatDuration(elapsed);
    } else if (const auto left = eta_.remaining()) {
      time = "ETA " + formatDuration(*left);
    } else {
      time = "ETA --";
    }
    // Percent rounds down so that 100% only ever means finished.
    line = fmt::format("{} [{}{}] {:3d}% {}", event.phase, std::string(filled, '#'),
                       std::string(kBarWidth - filled, '.'), int(f * 100.0), time);
  } else {
    line = fmt::format("{} {}", event.phase, formatDuration(elapsed));
  }
  if (!event.detail.empty()) line += fmt::format(" {}", event.detail);
  // A line that wraps cannot be redrawn with '\r', so keep it inside the terminal.
  truncateUtf8(line, size_t(std::max(terminalColumns() - 1, 1)));
  // '\r' returns to the line start; ESC[K erases what a longer previous line left behind.
  fmt::print(stderr, "\r{}\x1b[K", line);
  std::fflush(stderr);
  lineOpen_ = true;
}

// "luxel: solve 45% (eta 3.2s) unshot 1.2%"
void ProgressBar::printLogLine(const luxel::ProgressEvent& event, double elapsed, bool done) {
  std::string line = fmt::format("luxel: {}", event.phase);
  if (done) {
    line += fmt::format(" 100% ({})", formatDuration(elapsed));
  } else if (isKnown(event.fraction)) {
    const double f = event.fraction;
    line += fmt::format(" {}%", int(f * 100.0));
    if (const auto left = eta_.remaining()) line += fmt::format(" (eta {})", formatDuration(*left));
  } else {
    line += fmt::format(" ({})", formatDuration(elapsed));
  }
  if (!event.detail.empty()) line += fmt::format(" {}", event.detail);
  fmt::print(stderr, "{}\n", line);
}

}  // namespace luxel::cli
