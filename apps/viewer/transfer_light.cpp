#include "transfer_light.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "core/spherical_harmonics.h"
#include "luxel/error.h"

namespace luxel::viewer {
namespace {

// The scene's horizontal frame: east, north (the `sun` action's; -z projected is north of east).
std::pair<Vec3, Vec3> horizon(Vec3 up) {
  up = glm::length(up) > 0.0f ? glm::normalize(up) : Vec3(0.0f, 1.0f, 0.0f);
  Vec3 ahead = Vec3(0, 0, -1) - up * glm::dot(Vec3(0, 0, -1), up);
  if (glm::length(ahead) < 1e-4f) ahead = Vec3(0, 1, 0) - up * glm::dot(Vec3(0, 1, 0), up);  // a z-up scene
  const Vec3 east = glm::normalize(glm::cross(ahead, up));
  return {east, glm::cross(up, east)};
}

// Comma-separated finite numbers.
std::vector<float> numbers(const std::string& text, const std::string& what) {
  std::vector<float> out;
  size_t at = 0;
  while (true) {
    const size_t comma = text.find(',', at);
    const std::string part = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    char* end = nullptr;
    const float v = std::strtof(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(v)) throw Error(fmt::format("{}: '{}' is not a finite number", what, part));
    out.push_back(v);
    if (comma == std::string::npos) return out;
    at = comma + 1;
  }
}

}  // namespace

std::vector<Rgb> transferLightSh(const BakedGlb::TransferLight& light, Rgb skyScale) {
  const size_t n = size_t(light.bands * light.bands);
  if (light.bands < 2 || light.bands > 4 || light.sky.size() != n)
    throw Error(fmt::format("a {}-band transfer light with {} sky coefficients", light.bands, light.sky.size()));
  std::vector<Rgb> sh(n);
  for (size_t i = 0; i < n; ++i) sh[i] = light.sky[i] * skyScale;
  for (const BakedGlb::TransferSun& sun : light.suns) {
    const auto y = shBasis16(-glm::normalize(sun.direction));
    for (size_t i = 0; i < n; ++i) sh[i] += y[i] * sun.irradiance;
  }
  return sh;
}

Vec3 sunTravelDirection(Vec3 sceneUp, float azimuth, float elevation) {
  const auto [east, north] = horizon(sceneUp);
  const float az = glm::radians(azimuth), el = glm::radians(elevation);
  const Vec3 towardsSun = (east * std::cos(az) + north * std::sin(az)) * std::cos(el) + glm::cross(east, north) * std::sin(el);
  return -towardsSun;
}

std::pair<float, float> sunAngles(Vec3 sceneUp, Vec3 travelDirection) {
  const auto [east, north] = horizon(sceneUp);
  const Vec3 t = -glm::normalize(travelDirection);
  const float el = std::asin(std::clamp(glm::dot(t, glm::cross(east, north)), -1.0f, 1.0f));
  return {glm::degrees(std::atan2(glm::dot(t, north), glm::dot(t, east))), glm::degrees(el)};
}

Vec3 parseDirection(const std::string& text, const std::string& what) {
  const std::vector<float> v = numbers(text, what);
  if (v.size() != 3) throw Error(fmt::format("{}: '{}' is not X,Y,Z (three numbers and two commas)", what, text));
  const Vec3 d(v[0], v[1], v[2]);
  const float largest = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  if (!(largest > 0.0f)) throw Error(fmt::format("{}: the direction is zero", what));
  return glm::normalize(d / largest);  // divided first: 1e38 squared is not a float
}

Rgb parseColour(const std::string& text, const std::string& what) {
  const std::vector<float> v = numbers(text, what);
  if (v.size() != 1 && v.size() != 3) throw Error(fmt::format("{}: '{}' is not V or R,G,B", what, text));
  const Rgb c = v.size() == 1 ? Rgb(v[0]) : Rgb(v[0], v[1], v[2]);
  if (glm::any(glm::lessThan(c, Rgb(0.0f)))) throw Error(fmt::format("{}: '{}' is negative", what, text));
  return c;
}

}  // namespace luxel::viewer
