#include "solve/method_choice.h"

namespace luxel {

std::string chooseMethod(const std::string& method, const std::string& backend, size_t patches, bool followsChanges) {
  if (method != "auto") return method;
  if (backend == "gl") return followsChanges ? "cross-redistribution" : "progressive";
  if (patches > kHierarchicalPatches) return "hierarchical";
  return followsChanges ? "cross-redistribution" : "progressive";
}

}  // namespace luxel
