// Resource readers: files under a folder, and bytes held in memory (luxel/resources.h).
#include "luxel/resources.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "luxel/error.h"
#include "scene/import/resource_path.h"

namespace luxel {

namespace fs = std::filesystem;

std::string normalizeResourcePath(std::string_view path) {
  std::string s(path);
  std::replace(s.begin(), s.end(), '\\', '/');
  s = fs::path(s).lexically_normal().generic_string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s == "." ? std::string() : s;
}

std::string resourceFolder(std::string_view path) {
  size_t slash = path.rfind('/');
  if (slash == std::string_view::npos) return {};
  return std::string(path.substr(0, slash == 0 ? 1 : slash));  // "/a.png" is in "/"
}

// ---- ResourceReader defaults --------------------------------------------------------------------

bool ResourceReader::exists(std::string_view path) const { return read(path).has_value(); }

std::vector<std::string> ResourceReader::list(std::string_view) const { return {}; }

std::string ResourceReader::describe(std::string_view path) const { return std::string(path); }

// ---- files --------------------------------------------------------------------------------------

FileResourceReader::FileResourceReader(fs::path root) : root_(std::move(root)) {}

fs::path FileResourceReader::file(std::string_view path) const {
  // An absolute path replaces the root (operator/), as the file-path loaders resolved them.
  return path.empty() ? root_ : root_ / fs::path(std::string(path));
}

std::optional<std::vector<std::byte>> FileResourceReader::read(std::string_view path) const {
  const fs::path f = file(path);
  std::error_code ec;
  if (!fs::is_regular_file(f, ec)) return std::nullopt;
  std::ifstream in(f, std::ios::binary);
  if (!in) throw Error(fmt::format("'{}': cannot open file", describe(path)));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0) throw Error(fmt::format("'{}': read error", describe(path)));
  std::vector<std::byte> bytes(static_cast<size_t>(size));
  if (!bytes.empty() && !in.read(reinterpret_cast<char*>(bytes.data()), size))
    throw Error(fmt::format("'{}': read error", describe(path)));
  return bytes;
}

bool FileResourceReader::exists(std::string_view path) const {
  std::error_code ec;
  return fs::is_regular_file(file(path), ec);
}

std::vector<std::string> FileResourceReader::list(std::string_view folder) const {
  std::vector<std::string> names;
  std::error_code ec;
  // A reader rooted at "" (a model path without a folder) lists the working directory; "" alone
  // names no directory, and the case-insensitive texture fallback would find nothing.
  fs::path dir = file(folder);
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) return names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file(ec)) names.push_back(e.path().filename().string());
  return names;
}

std::string FileResourceReader::describe(std::string_view path) const {
  return file(path).lexically_normal().string();
}

// ---- memory -------------------------------------------------------------------------------------

void MemoryResourceReader::add(std::string_view path, std::span<const std::byte> bytes) {
  files_[normalizeResourcePath(path)].assign(bytes.begin(), bytes.end());
}

void MemoryResourceReader::add(std::string_view path, std::string_view bytes) {
  add(path, std::as_bytes(std::span<const char>(bytes.data(), bytes.size())));
}

std::optional<std::vector<std::byte>> MemoryResourceReader::read(std::string_view path) const {
  auto it = files_.find(normalizeResourcePath(path));
  if (it == files_.end()) return std::nullopt;
  return it->second;
}

bool MemoryResourceReader::exists(std::string_view path) const {
  return files_.find(normalizeResourcePath(path)) != files_.end();
}

std::vector<std::string> MemoryResourceReader::list(std::string_view folder) const {
  const std::string dir = normalizeResourcePath(folder);
  std::vector<std::string> names;
  for (const auto& [path, bytes] : files_) {
    if (resourceFolder(path) != dir) continue;
    size_t slash = path.rfind('/');
    names.push_back(slash == std::string::npos ? path : path.substr(slash + 1));
  }
  return names;
}

}  // namespace luxel
