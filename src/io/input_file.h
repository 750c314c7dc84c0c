// Why a path given as an input cannot be read as a file, in words a user acts on: a directory or a
// FIFO passed as a scene used to be reported as "no such file", and opening a FIFO would wait for
// a writer forever.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace luxel {

// nullopt for a regular file (or a link to one); otherwise "no such file", "is a directory", or
// "is not a regular file (a FIFO, socket or device)". Never opens the path.
std::optional<std::string> whyNotARegularFile(const std::filesystem::path& path);

}  // namespace luxel
