// Running a call on a thread with a large stack, for third-party code that recurses as deep as its
// input nests (Assimp's glTF and COLLADA importers, its scene validation, aiNode's destructor): a
// file nesting 20,000 nodes overflows a default 8 MiB stack and crashes the process.
#pragma once

#include <cstddef>
#include <functional>

namespace luxel {

// 1 GiB of address space, committed only as the recursion touches it: about a million nested nodes
// at the ~1 KiB a level Assimp's importers use.
inline constexpr size_t kLargeStackBytes = size_t(1) << 30;

// Runs `work` on a new thread with a `stackBytes` stack and waits for it. Whatever `work` throws is
// rethrown here. When no such thread can be made (address space limits), runs `work` here.
void runOnLargeStack(const std::function<void()>& work, size_t stackBytes = kLargeStackBytes);

}  // namespace luxel
