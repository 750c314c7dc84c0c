#include "output_paths.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "luxel/error.h"

namespace fs = std::filesystem;

namespace luxel::cli {
namespace {

// The atomic writer's temporary name is ".NAME.tmp-PID-COUNTER" beside the output: the name
// plus at most this many bytes.
constexpr size_t kTemporarySuffixBytes = 1 + 5 + 20 + 1 + 20;

}  // namespace

std::string lowerExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

void checkOutputPaths(const std::vector<OutputPath>& outputs) {
  std::vector<std::pair<fs::path, const OutputPath*>> seen;
  for (const OutputPath& o : outputs) {
    const fs::path p(o.path);
    const std::string what = fmt::format("{} {}", o.option, o.path);
    if (p.filename().empty()) throw Error(fmt::format("{}: not a file name", what));
    if (!o.extensions.empty() &&
        std::find(o.extensions.begin(), o.extensions.end(), lowerExtension(p)) == o.extensions.end())
      throw Error(fmt::format("{}: the file name must end in {}", what, fmt::join(o.extensions, " or ")));
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw Error(fmt::format("{}: directory '{}' does not exist", what, dir.string()));
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
      throw Error(fmt::format("{}: directory '{}' is not writable", what, dir.string()));
    const size_t nameMax = size_t(std::max(14L, ::pathconf(dir.c_str(), _PC_NAME_MAX)));
    if (p.filename().string().size() + kTemporarySuffixBytes > nameMax)
      throw Error(fmt::format("{}: the file name is {} bytes; at most {} fit beside the temporary file's suffix", what,
                              p.filename().string().size(), nameMax - kTemporarySuffixBytes));
    const fs::file_status status = fs::status(p, ec);
    if (fs::exists(status) && !fs::is_regular_file(status))
      throw Error(fmt::format("{}: is a {}, not a file", what, fs::is_directory(status) ? "directory" : "special file"));
    const fs::path same = fs::weakly_canonical(fs::absolute(p), ec);
    for (const auto& [other, by] : seen)
      if (other == same)
        throw Error(fmt::format("{} and {} {} name the same file", what, by->option, by->path));
    seen.emplace_back(same, &o);
  }
}

}  // namespace luxel::cli
