// Lightmap page encodings: RGBM 8-bit PNG (value = rgb/255 * alpha/255 * range, linear) decodes
// back within its quantisation, and the float EXR page reads back exactly.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <filesystem>
#include <memory>

#include "cli/cli_runner.h"
#include "luxel/image.h"
#include "luxel/lightmap.h"

namespace {

luxel::Image ramp() {
  luxel::Image img(16, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      img.at(x, y) = luxel::Rgb(0.01f + 0.7f * float(x), 0.002f * float(y), 3.0f * float(x * y) / 105.0f);
  return img;
}

TEST(LightmapEncoding, RgbmRoundTripsWithinQuantisation) {
  const luxel::Image img = ramp();
  const float range = luxel::rgbmRange(img);
  EXPECT_EQ(range, 16.0f);  // largest component 10.51 -> the next power of two
  const std::vector<uint8_t> png = luxel::encodeRgbmPng(img, range);
  int w = 0, h = 0, n = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_memory(png.data(), int(png.size()), &w, &h, &n, 4),
                                               stbi_image_free);
  ASSERT_TRUE(px) << "not a PNG";
  ASSERT_EQ(w, 16);
  ASSERT_EQ(h, 8);
  double worst = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const stbi_uc* p = px.get() + 4 * (y * w + x);
      const float m = float(p[3]) / 255.0f * range;
      const luxel::Rgb decoded(float(p[0]) / 255.0f * m, float(p[1]) / 255.0f * m, float(p[2]) / 255.0f * m);
      const luxel::Rgb want = img.at(x, y);
      for (int c = 0; c < 3; ++c) {
        // One step of the 8-bit colour at this pixel's multiplier, plus the multiplier's own step.
        const double step = m / 255.0 + double(want[c]) / 255.0;
        worst = std::max(worst, std::abs(double(decoded[c]) - double(want[c])) / step);
      }
    }
  EXPECT_LE(worst, 1.0) << "decoded values off by more than one quantisation step";
}

TEST(LightmapEncoding, ExrPageReadsBackExactly) {
  const luxel::Image img = ramp();
  const std::filesystem::path path = std::filesystem::path(LUXEL_TEST_TMP) / "lightmap-page.exr";
  std::filesystem::create_directories(path.parent_path());
  luxel::writeImage(img, path, luxel::ToneMap{});
  const luxel::Image back = luxel::readExr(path);
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(back.pixels[i], img.pixels[i]) << i;
}

TEST(LightmapEncoding, BakeCommandWritesTheGlbAndFloatPages) {
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"bake", "cornell", "-o", "c.glb", "--lightmaps", "--elements", "2000"});
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / "c.glb"));
  ASSERT_TRUE(fs::exists(dir / "c.lightmap0.exr")) << r.out;
  const luxel::Image page = luxel::readExr(dir / "c.lightmap0.exr");
  double lit = 0.0;
  for (const luxel::Rgb& c : page.pixels) {
    ASSERT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
    ASSERT_GE(std::min({c.r, c.g, c.b}), 0.0f);
    lit += c.g;
  }
  EXPECT_GT(lit, 0.0);  // irradiance was baked, not a black page
}

}  // namespace
