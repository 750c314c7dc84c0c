// 8-bit sRGB PNG output through stb_image_write, and the writer chosen by file extension.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <stb_image_write.h>

#include "io/atomic_file.h"
#include "luxel/error.h"
#include "luxel/image.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;

// Display value in [0,1] to an 8-bit code, rounding to nearest. toneMap already removes NaN;
// checking again keeps this safe on its own.
uint8_t toByte(float v) {
  if (!(v > 0.0f)) return 0;
  return uint8_t(std::lround(std::min(v, 1.0f) * 255.0f));
}

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return ext;
}

}  // namespace

void writePng(const Image& image, const fs::path& path, const ToneMap& options) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != size_t(image.width) * size_t(image.height)) {
    throw Error(fmt::format("{}: cannot write an empty or inconsistent {}x{} image", path.string(),
                            image.width, image.height));
  }
  const std::vector<Rgb> display = toneMap(image, options);
  std::vector<uint8_t> bytes(display.size() * 3);
  for (size_t i = 0; i < display.size(); ++i) {
    bytes[3 * i + 0] = toByte(display[i].x);
    bytes[3 * i + 1] = toByte(display[i].y);
    bytes[3 * i + 2] = toByte(display[i].z);
  }
  // Encoded in memory and written through OutputFile: stb's own file writer ignores write errors.
  std::vector<unsigned char> png;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
  };
  // Row 0 is the top row in both Image and PNG, so no flip is needed.
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, bytes.data(), image.width * 3))
    throw Error(fmt::format("{}: cannot encode the PNG", path.string()));
  writeFileAtomically(path, [&](const fs::path& tmp) {
    OutputFile out(tmp);
    out.write(png.data(), png.size());
    out.close();
  });
}

void writeImage(const Image& image, const fs::path& path, const ToneMap& options) {
  // The last line of defence: the solvers and renderers stop on non-finite values, and an image
  // that still holds one is a defect to report, not a file to write.
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const Rgb& c = image.pixels[i];
    if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b))
      throw Error(fmt::format("{}: not written: pixel ({}, {}) is not finite", path.string(),
                              image.width > 0 ? i % size_t(image.width) : 0, image.width > 0 ? i / size_t(image.width) : 0));
  }
  const std::string ext = lowerExtension(path);
  if (ext == ".exr") {
    writeExr(image, path);
  } else if (ext == ".png") {
    writePng(image, path, options);
  } else {
    const std::string what = ext.empty() ? "no file extension"
                                         : fmt::format("unsupported image extension '{}'",
                                                       path.extension().string());
    throw Error(fmt::format("{}: {} (use .exr or .png)", path.string(), what));
  }
}

}  // namespace luxel
