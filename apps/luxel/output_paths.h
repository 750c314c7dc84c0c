// Every file a command will write, checked before any work: a run that can only fail at the end,
// after a long solve and with some outputs already written, is checked at the start instead.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace luxel::cli {

struct OutputPath {
  std::string option;  // how the user gave it, for messages: "-o", "--stats", ...
  std::string path;
  std::vector<std::string> extensions;  // allowed, lower case with the dot; empty: any
};

// Throws Error naming the option and path when one has an extension not allowed, its folder does
// not exist or cannot be written, it names a folder or something other than a regular file, its
// name is too long for the temporary file written beside it, or two outputs name one file.
void checkOutputPaths(const std::vector<OutputPath>& outputs);

// The extension of `path` in lower case, with its dot: ".png".
std::string lowerExtension(const std::filesystem::path& path);

}  // namespace luxel::cli
