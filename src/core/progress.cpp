#include "luxel/progress.h"

#include "luxel/error.h"

namespace luxel {

void reportProgress(const ProgressCallback& cb, std::string_view phase, double fraction,
                    std::string_view detail) {
  if (cb && !cb(ProgressEvent{phase, fraction, detail})) throw Cancelled();
}

}  // namespace luxel
