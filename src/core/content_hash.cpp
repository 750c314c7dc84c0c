#include "core/content_hash.h"

#include <xxhash.h>

namespace luxel {

struct ContentHash::State {
  XXH3_state_t* s = XXH3_createState();
  ~State() { XXH3_freeState(s); }
};

ContentHash::ContentHash() : state_(std::make_unique<State>()) { XXH3_64bits_reset(state_->s); }
ContentHash::~ContentHash() = default;

void ContentHash::bytes(const void* data, size_t size) { XXH3_64bits_update(state_->s, data, size); }

uint64_t ContentHash::digest() const { return XXH3_64bits_digest(state_->s); }

}  // namespace luxel
