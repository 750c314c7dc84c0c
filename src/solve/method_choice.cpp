#include "solve/method_choice.h"

namespace luxel {

std::string chooseMethod(const std::string& method, const std::string& backend, size_t patches) {
  if (method != "auto") return method;
  if (backend == "gl") return "progressive";
  return patches > kHierarchicalPatches ? "hierarchical" : "progressive";
}

}  // namespace luxel
