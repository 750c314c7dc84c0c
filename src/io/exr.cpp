// OpenEXR input and output of linear radiance as 32-bit float RGB.
//
// Imf::RgbaOutputFile only writes half floats, whose 65504 maximum and 11-bit mantissa lose
// radiance values, so this uses the general Imf::OutputFile / Imf::InputFile interface with FLOAT
// slices ("Reading and Writing OpenEXR Image Files with the OpenEXR Library", openexr.com).
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <fmt/format.h>

#include "io/atomic_file.h"
#include "luxel/error.h"
#include "luxel/image.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;

// The slices below point straight into Image::pixels, which needs tightly packed float triples.
static_assert(sizeof(Rgb) == 3 * sizeof(float), "Rgb must be three packed floats");

constexpr const char* kChannels[3] = {"R", "G", "B"};
// Refuse absurd headers before allocating: 2^30 pixels is 12 GiB of float RGB.
constexpr int64_t kMaxPixels = int64_t(1) << 30;

}  // namespace

void writeExr(const Image& image, const fs::path& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != size_t(image.width) * size_t(image.height)) {
    throw Error(fmt::format("{}: cannot write an empty or inconsistent {}x{} image", path.string(),
                            image.width, image.height));
  }
  writeFileAtomically(path, [&](const fs::path& tmp) {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;  // lossless, and the usual choice for renders
    for (const char* name : kChannels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));

    // OpenEXR only reads from the frame buffer, but its Slice takes a non-const pointer.
    char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data()));
    const size_t xStride = sizeof(Rgb);
    const size_t yStride = sizeof(Rgb) * size_t(image.width);
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c) {
      frame.insert(kChannels[c],
                   Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
    }
    try {
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    } catch (const std::exception& e) {
      throw Error(fmt::format("cannot write EXR: {}", e.what()));
    }
  });
}

Image readExr(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw Error(fmt::format("{}: no such file", path.string()));
  }
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int64_t width = int64_t(window.max.x) - window.min.x + 1;
    const int64_t height = int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width * height > kMaxPixels) {
      throw Error(fmt::format("{}: unsupported image size {}x{}", path.string(), width, height));
    }

    const Imf::ChannelList& channels = file.header().channels();
    for (const char* name : kChannels) {
      const Imf::Channel* channel = channels.findChannel(name);
      if (!channel) {
        throw Error(fmt::format("{}: missing channel '{}' (need R, G and B)", path.string(), name));
      }
      if (channel->xSampling != 1 || channel->ySampling != 1) {
        throw Error(fmt::format("{}: channel '{}' is subsampled, which is not supported",
                                path.string(), name));
      }
    }

    Image image(static_cast<int>(width), static_cast<int>(height));
    char* base = reinterpret_cast<char*>(image.pixels.data());
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c) {
      // Make() offsets the pointer by the data window's origin; half and uint channels are
      // converted to float by the library.
      frame.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), window,
                                                  sizeof(Rgb), sizeof(Rgb) * size_t(width)));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: cannot read EXR: {}", path.string(), e.what()));
  }
}

}  // namespace luxel
