// Images: linear radiance in memory, EXR (float) and tone-mapped PNG on disk.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

// Linear RGB radiance, row 0 at the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;
  // Per pixel, the share of its samples whose primary ray hit a surface (renders fill it); empty:
  // unknown, every pixel counts as covered. Automatic exposure meters on covered pixels only.
  std::vector<float> coverage;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), Rgb(0.0f)) {}
  Rgb& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  const Rgb& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

struct ToneMap {
  enum class Curve { Filmic, Reinhard, Clamp };
  Curve curve = Curve::Filmic;
  // Exposure in stops, added to the automatic exposure when autoExposure is on.
  float exposure = 0.0f;
  // Scale so that the log-average luminance of the pixels that show a surface maps to middle
  // grey (0.18): see autoExposureScale.
  bool autoExposure = true;
};

// The multiplier automatic exposure applies: middle grey (0.18) over the log-average luminance
// (Reinhard et al. 2002), each pixel weighted by its coverage, so that background (black, or a sky)
// does not pull the exposure. With no coverage, or none covered, every pixel counts equally;
// an image with no light at all gets 1. Throws Error when coverage is neither empty nor one per pixel.
double autoExposureScale(const Image& image);

// Parses "filmic", "reinhard" or "clamp"; throws Error otherwise.
ToneMap::Curve parseToneCurve(const std::string& name);

// Maps linear radiance to display-referred sRGB in [0,1] (exposure, curve, sRGB transfer).
std::vector<Rgb> toneMap(const Image& image, const ToneMap& options);

// Writers write to a temporary file beside `path` and rename it, so a failure never leaves a
// half-written file. They throw Error naming the path on failure.
void writeExr(const Image& image, const std::filesystem::path& path);  // 32-bit float RGB
void writePng(const Image& image, const std::filesystem::path& path, const ToneMap& options);
// Chooses by extension (.exr or .png); throws Error for anything else.
void writeImage(const Image& image, const std::filesystem::path& path, const ToneMap& options);

// Reads an RGB(A) EXR into linear radiance; throws Error naming the file when it cannot.
Image readExr(const std::filesystem::path& path);

}  // namespace luxel
