// What every transport does unless it says otherwise (transport/transport.h).
#include "transport/transport.h"

#include "luxel/error.h"

namespace luxel {

void Transport::lightSh(std::span<const uint32_t>, int, std::span<Rgb>) {
  throw Error("this transport does not record where the analytic light comes from (directional bakes need the CPU transport)");
}

}  // namespace luxel
