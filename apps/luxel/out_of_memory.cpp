#include "out_of_memory.h"

#include <utility>

namespace luxel::cli {
namespace {

// One command runs per process, on the main thread: plain strings suffice. They are set before
// the work that may run out, so the message never allocates much when memory is short.
std::string g_doing;
std::string g_hint;

}  // namespace

void nowDoing(std::string doing, std::string hint) {
  g_doing = std::move(doing);
  g_hint = std::move(hint);
}

std::string outOfMemoryMessage() {
  if (g_doing.empty()) return "out of memory";
  return "out of memory while " + g_doing + ": " + g_hint;
}

}  // namespace luxel::cli
