// The solver `auto` picks for a scene: the flat progressive solver where it is fast and the most
// accurate, the face-cluster hierarchy (seed 002) where its cost, quadratic in the patches,
// would be minutes. The rule and the measurements behind it are in docs/algorithms.md
// ("Choosing a solver").
#pragma once

#include <cstddef>
#include <string>

namespace luxel {

// Above this many patches (shooters) `auto` solves with the hierarchy.
inline constexpr size_t kHierarchicalPatches = 5000;

// The methods `auto` chooses between.
inline constexpr const char* kAutoMethods[] = {"progressive", "hierarchical", "cross-redistribution", "incremental"};

// `method` itself unless it is "auto"; then progressive on the GL backend (the hierarchy runs on
// the CPU only) or at most kHierarchicalPatches patches, hierarchical above. For a session that
// will follow moves and edits (`followsChanges`: an animation, a viewer), the dynamic solver in
// progressive's place: cross-redistribution, on either backend.
std::string chooseMethod(const std::string& method, const std::string& backend, size_t patches,
                         bool followsChanges = false);

}  // namespace luxel
