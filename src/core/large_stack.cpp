#include "core/large_stack.h"

#include <pthread.h>

#include <exception>

namespace luxel {
namespace {

struct Call {
  const std::function<void()>* work;
  std::exception_ptr error;
};

extern "C" void* runCall(void* argument) {
  auto* call = static_cast<Call*>(argument);
  try {
    (*call->work)();
  } catch (...) {
    call->error = std::current_exception();
  }
  return nullptr;
}

}  // namespace

void runOnLargeStack(const std::function<void()>& work, size_t stackBytes) {
  Call call{&work, nullptr};
  pthread_attr_t attributes;
  bool started = false;
  pthread_t thread;
  if (pthread_attr_init(&attributes) == 0) {
    started = pthread_attr_setstacksize(&attributes, stackBytes) == 0 &&
              pthread_create(&thread, &attributes, runCall, &call) == 0;
    pthread_attr_destroy(&attributes);
  }
  if (!started) {
    work();
    return;
  }
  pthread_join(thread, nullptr);
  if (call.error) std::rethrow_exception(call.error);
}

}  // namespace luxel
