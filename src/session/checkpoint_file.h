// A checkpoint on disk: a header (magic, format, the key of the solve it belongs to, the payload's
// length and XXH3 checksum) and the payload, the solver host's and solver's state. Written
// atomically, so a kill while writing leaves the previous checkpoint whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace luxel {

void writeCheckpointFile(const std::filesystem::path& path, uint64_t key, std::span<const std::byte> payload);

// The payload of the checkpoint at `path`, after checking that it is a whole luxel checkpoint
// written for the solve `key` names. Throws Error saying which of those it is not.
std::vector<std::byte> readCheckpointFile(const std::filesystem::path& path, uint64_t key);

}  // namespace luxel
