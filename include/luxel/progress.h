// Progress reporting that can cancel. The library never prints: it calls this, and the caller
// decides what to show. Return false from the callback to cancel; the call then throws Cancelled.
#pragma once

#include <functional>
#include <string_view>

namespace luxel {

struct ProgressEvent {
  std::string_view phase;  // "form factors", "solve", "render", ...
  double fraction = 0.0;   // 0..1 within the phase, or < 0 when unknown
  std::string_view detail; // e.g. "unshot 1.2%"
};

using ProgressCallback = std::function<bool(const ProgressEvent&)>;

// Calls `cb` if set and throws Cancelled when it returns false.
void reportProgress(const ProgressCallback& cb, std::string_view phase, double fraction,
                    std::string_view detail = {});

}  // namespace luxel
