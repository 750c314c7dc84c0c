// Progress display for the command-line tool: a redrawn bar on a terminal, sparse log lines
// otherwise, nothing when quiet. It also turns Ctrl-C into a clean cancel.
#pragma once

#include <signal.h>

#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "luxel/progress.h"
#include "luxel/progress_eta.h"

namespace luxel::cli {

class ProgressBar {
 public:
  // Installs a SIGINT handler (even when quiet) that makes update() return false, so the library
  // stops at its next progress report and throws Cancelled. A second Ctrl-C, or a SIGTERM, ends the
  // process the usual way after removing any output's temporary file. The destructor restores the
  // previous handlers.
  explicit ProgressBar(bool quiet);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Also records every report as a line "SECONDS\tPHASE\tFRACTION\tDETAIL" (seconds since the
  // bar was made), for `--progress-trace` (tests/data/progress/ holds such traces). Throws Error
  // when the folder of `path` does not exist.
  void traceTo(const std::string& path);
  // Writes the trace (atomically), once; the destructor writes it when this was not called (a
  // cancelled or failed run). Throws Error naming the file when it cannot be written.
  void writeTrace();

  // Shows `event` and returns false once Ctrl-C was pressed. Safe to call from any thread.
  bool update(const luxel::ProgressEvent& event);
  // Ends the current terminal line, so that what is printed next starts on its own line.
  void finish();
  // update() wrapped for the library; the ProgressBar must outlive the returned callback.
  luxel::ProgressCallback callback();

  // True once Ctrl-C was pressed since the last ProgressBar was constructed.
  static bool interrupted();

 private:
  using Clock = std::chrono::steady_clock;

  void drawTerminal(const luxel::ProgressEvent& event, double elapsed, bool done);
  void printLogLine(const luxel::ProgressEvent& event, double elapsed, bool done);
  void finishLocked();

  bool quiet_;
  bool terminal_;
  std::mutex mutex_;
  std::string phase_;
  bool havePhase_ = false;
  bool phaseDone_ = false;  // the 100% state of this phase has been shown
  bool lineOpen_ = false;   // terminal: a line is drawn and not yet ended
  Clock::time_point phaseStart_;
  luxel::EtaEstimator eta_;  // of the current phase
  Clock::time_point lastOutput_;
  Clock::time_point created_ = Clock::now();
  std::string tracePath_;
  std::vector<std::string> trace_;
  struct sigaction previousSigint_ {};
  struct sigaction previousSigterm_ {};
};

}  // namespace luxel::cli
