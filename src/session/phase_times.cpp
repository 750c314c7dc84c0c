#include "luxel/solution.h"

namespace luxel {

std::vector<PhaseTime> phasesSince(const std::vector<PhaseTime>& before, const std::vector<PhaseTime>& after) {
  std::vector<PhaseTime> since;
  for (const PhaseTime& p : after) {
    PhaseTime d = p;
    for (const PhaseTime& b : before)
      if (b.name == p.name && b.count <= p.count)
        d.count -= b.count, d.secondsGpu -= b.secondsGpu, d.secondsCpu -= b.secondsCpu;
    if (d.count > 0) since.push_back(d);
  }
  return since;
}

}  // namespace luxel
