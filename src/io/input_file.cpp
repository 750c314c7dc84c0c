#include "io/input_file.h"

#include <system_error>

namespace luxel {

std::optional<std::string> whyNotARegularFile(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  switch (status.type()) {
    case std::filesystem::file_type::regular: return std::nullopt;
    case std::filesystem::file_type::directory: return "is a directory";
    case std::filesystem::file_type::not_found:
    case std::filesystem::file_type::none: return "no such file";
    default: return "is not a regular file (a FIFO, socket or device)";
  }
}

}  // namespace luxel
