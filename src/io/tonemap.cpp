// Tone mapping: linear radiance to display-referred sRGB in [0,1].
//
// Three steps per pixel:
//  1. Exposure. Automatic exposure follows Reinhard et al. 2002, "Photographic Tone Reproduction
//     for Digital Images", eq. 1-2: the log-average luminance exp(mean(log(delta + Lw))) is mapped
//     to middle grey (key 0.18), then scaled by 2^exposure. The mean is over the pixels that show
//     a surface (Image::coverage): black background around a model is not part of the scene.
//  2. A curve: the ACES filmic fit (Narkowicz 2016, "ACES Filmic Tone Mapping Curve",
//     knarkowicz.wordpress.com/2016/01/06/aces-filmic-tone-mapping-curve/), Reinhard's simple
//     operator L/(1+L) (Reinhard et al. 2002, eq. 3), or a clamp.
//  3. The sRGB transfer function (IEC 61966-2-1:1999).
// Luminance uses the Rec. 709 / sRGB primaries (ITU-R BT.709-6):
// Y = 0.2126 R + 0.7152 G + 0.0722 B.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/image.h"
#include "scene/texture_decode.h"

namespace luxel {
namespace {

constexpr float kMiddleGrey = 0.18f;
// Reinhard's delta, which keeps log() finite on black pixels. It is relative to the mean
// luminance, not absolute, so the exposure does not depend on the scene's units (W or lm).
constexpr double kLogAverageDelta = 1e-4;
// Scaled values are clamped here before the curves: far brighter than white under every curve,
// yet small enough that x * x stays finite in float.
constexpr float kMaxScaled = 1e18f;

// Rec. 709 luminance. Works on the components by index: the library builds with
// GLM_FORCE_XYZW_ONLY, so .r/.g/.b are not available.
float luminance(const Rgb& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

bool isFinite(const Rgb& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

}  // namespace

double autoExposureScale(const Image& image) {
  if (!image.coverage.empty() && image.coverage.size() != image.pixels.size())
    throw Error(fmt::format("auto exposure: {} coverage values for {} pixels", image.coverage.size(),
                            image.pixels.size()));
  // Each pixel weighted by the share of its samples that hit a surface; all alike when none did.
  std::vector<double> weight(image.pixels.size(), 1.0);
  double covered = 0.0;
  for (size_t i = 0; i < image.coverage.size(); ++i) {
    const float c = image.coverage[i];
    covered += weight[i] = std::isfinite(c) ? std::clamp(double(c), 0.0, 1.0) : 0.0;
  }
  if (!(covered > 0.0)) std::fill(weight.begin(), weight.end(), 1.0);
  double sum = 0.0, weights = 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const Rgb& c = image.pixels[i];
    if (!isFinite(c)) continue;
    sum += weight[i] * std::max(0.0, double(luminance(c)));
    weights += weight[i];
  }
  if (!(weights > 0.0) || !(sum > 0.0) || !std::isfinite(sum)) return 1.0;
  const double delta = kLogAverageDelta * (sum / weights);

  double logSum = 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const Rgb& c = image.pixels[i];
    if (!isFinite(c)) continue;
    logSum += weight[i] * std::log(delta + std::max(0.0, double(luminance(c))));
  }
  const double logAverage = std::exp(logSum / weights);
  return kMiddleGrey / logAverage;
}

namespace {

// NaN and negative values become 0 so that no curve, and no PNG writer, ever sees them.
float sanitize(float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, kMaxScaled); }

float acesFilmic(float x) {
  constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}


Rgb applyCurve(const Rgb& c, ToneMap::Curve curve) {
  switch (curve) {
    case ToneMap::Curve::Filmic:
      // Per channel, as in Narkowicz's fit: bright saturated colours desaturate towards white.
      return Rgb(acesFilmic(c.x), acesFilmic(c.y), acesFilmic(c.z));
    case ToneMap::Curve::Reinhard: {
      // On luminance, as in the paper, scaling RGB by Ld/Lw = 1/(1+L): this keeps hue and
      // saturation, so a saturated colour can exceed 1 in one channel and is clamped there.
      const float scale = 1.0f / (1.0f + luminance(c));
      return glm::min(c * scale, Rgb(1.0f));
    }
    case ToneMap::Curve::Clamp:
      return glm::min(c, Rgb(1.0f));
  }
  return c;
}

}  // namespace

ToneMap::Curve parseToneCurve(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  if (lower == "filmic") return ToneMap::Curve::Filmic;
  if (lower == "reinhard") return ToneMap::Curve::Reinhard;
  if (lower == "clamp") return ToneMap::Curve::Clamp;
  throw Error(fmt::format("unknown tone curve '{}' (expected filmic, reinhard or clamp)", name));
}

std::vector<Rgb> toneMap(const Image& image, const ToneMap& options) {
  double scale = std::exp2(double(options.exposure));
  if (options.autoExposure) scale *= autoExposureScale(image);
  const float s = float(scale);

  std::vector<Rgb> out(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const Rgb& p = image.pixels[i];
    const Rgb exposed(sanitize(p.x * s), sanitize(p.y * s), sanitize(p.z * s));
    const Rgb mapped = applyCurve(exposed, options.curve);
    out[i] = Rgb(linearToSrgb(mapped.x), linearToSrgb(mapped.y), linearToSrgb(mapped.z));
  }
  return out;
}

}  // namespace luxel
