// Image output: EXR round trips, tone-mapping closed forms, PNG contents, and failures that
// must name the file and leave nothing behind.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <stb_image.h>

#include "io/atomic_file.h"
#include "luxel/error.h"
#include "luxel/image.h"

namespace {

namespace fs = std::filesystem;
using luxel::Image;
using luxel::Rgb;
using luxel::ToneMap;

// A fresh folder per test, so tests can run in parallel and list what they left behind.
fs::path scratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "image" /
                 (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> listDir(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  return names;
}

// The message of the luxel::Error that `f` throws, or a test failure when it throws none.
template <class F>
std::string errorMessage(F&& f) {
  try {
    f();
  } catch (const luxel::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected luxel::Error";
  return {};
}

// Reference formulas, written out independently of src/io/tonemap.cpp.
double srgb(double v) {  // IEC 61966-2-1
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}
double aces(double x) {  // Narkowicz's ACES fit
  return std::min(1.0, (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14));
}
double rec709Luminance(double r, double g, double b) {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

ToneMap fixedExposure(ToneMap::Curve curve, float exposure = 0.0f) {
  ToneMap options;
  options.curve = curve;
  options.exposure = exposure;
  options.autoExposure = false;
  return options;
}

Image constantImage(int w, int h, Rgb value) {
  Image image(w, h);
  for (Rgb& p : image.pixels) p = value;
  return image;
}

uint32_t bits(float v) {
  uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// ---- EXR ------------------------------------------------------------------------------------

TEST(Exr, RoundTripIsBitExact) {
  const fs::path path = scratchDir() / "round.exr";
  Image image(4, 3);
  const float values[] = {0.0f, 1.0f, 0.1f, 1e6f, 1e6f + 1.0f, 1e-6f, 1e-30f,
                          1e-40f /* subnormal */, -2.5f, 3.14159265f, 65504.0f * 4.0f,
                          std::numeric_limits<float>::max(), 123456.789f};
  size_t k = 0;
  for (Rgb& p : image.pixels) {
    p = Rgb(values[k % 13], values[(k + 5) % 13], values[(k + 9) % 13]);
    ++k;
  }
  luxel::writeExr(image, path);
  const Image back = luxel::readExr(path);
  ASSERT_EQ(back.width, 4);
  ASSERT_EQ(back.height, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(bits(back.pixels[i][c]), bits(image.pixels[i][c])) << "pixel " << i << " c " << c;
    }
  }
  // Row order: row 0 stays at the top.
  EXPECT_EQ(bits(back.at(0, 0).x), bits(image.at(0, 0).x));
  EXPECT_EQ(bits(back.at(3, 2).z), bits(image.at(3, 2).z));
  EXPECT_EQ(listDir(path.parent_path()), std::vector<std::string>{"round.exr"});
}

TEST(Exr, WritesFloatChannelsWithZip) {
  const fs::path path = scratchDir() / "format.exr";
  luxel::writeExr(constantImage(2, 2, Rgb(1.0f)), path);
  Imf::InputFile file(path.c_str());
  EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
  int count = 0;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    EXPECT_EQ(it.channel().type, Imf::FLOAT) << it.name();
    ++count;
  }
  EXPECT_EQ(count, 3);
}

TEST(Exr, MissingChannelNamesFileAndChannel) {
  const fs::path path = scratchDir() / "luminance.exr";
  {
    Imf::Header header(2, 2);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    std::vector<float> y(4, 0.5f);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), sizeof(float),
                                 2 * sizeof(float)));
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(2);
  }
  const std::string message = errorMessage([&] { luxel::readExr(path); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("'R'"), std::string::npos) << message;
}

TEST(Exr, GarbageFileThrowsErrorNamingIt) {
  const fs::path path = scratchDir() / "garbage.exr";
  std::ofstream(path) << "this is not an OpenEXR file, just some text long enough to parse";
  const std::string message = errorMessage([&] { luxel::readExr(path); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST(Exr, MissingFileThrowsErrorNamingIt) {
  const fs::path path = scratchDir() / "absent.exr";
  const std::string message = errorMessage([&] { luxel::readExr(path); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST(Exr, EmptyImageThrows) {
  const fs::path dir = scratchDir();
  const std::string message = errorMessage([&] { luxel::writeExr(Image(), dir / "empty.exr"); });
  EXPECT_NE(message.find("empty.exr"), std::string::npos) << message;
  EXPECT_TRUE(listDir(dir).empty());
}

// ---- tone mapping -----------------------------------------------------------------------------

TEST(ToneMap, ParsesCurveNames) {
  EXPECT_EQ(luxel::parseToneCurve("filmic"), ToneMap::Curve::Filmic);
  EXPECT_EQ(luxel::parseToneCurve("reinhard"), ToneMap::Curve::Reinhard);
  EXPECT_EQ(luxel::parseToneCurve("clamp"), ToneMap::Curve::Clamp);
  EXPECT_EQ(luxel::parseToneCurve("Filmic"), ToneMap::Curve::Filmic);
  const std::string message = errorMessage([] { luxel::parseToneCurve("aces2"); });
  EXPECT_NE(message.find("aces2"), std::string::npos) << message;
}

TEST(ToneMap, SrgbTransferAtKnownPoints) {
  // Clamp with exposure 0 leaves values in [0,1] untouched, isolating the transfer function.
  Image image(4, 1);
  image.at(0, 0) = Rgb(0.0f);
  image.at(1, 0) = Rgb(0.0031308f);
  image.at(2, 0) = Rgb(1.0f);
  image.at(3, 0) = Rgb(0.5f);
  const auto out = luxel::toneMap(image, fixedExposure(ToneMap::Curve::Clamp));
  EXPECT_EQ(out[0].x, 0.0f);
  EXPECT_NEAR(out[1].x, 12.92 * 0.0031308, 1e-6);  // the linear segment's end, 0.0404500
  EXPECT_NEAR(out[1].x, 1.055 * std::pow(0.0031308, 1 / 2.4) - 0.055, 2e-6);  // continuous
  EXPECT_NEAR(out[2].x, 1.0, 1e-6);
  EXPECT_NEAR(out[3].x, 0.7353569, 1e-6);
}

TEST(ToneMap, ClampClosedForm) {
  Image image(3, 1);
  image.at(0, 0) = Rgb(0.25f, 7.0f, -1.0f);
  image.at(1, 0) = Rgb(0.5f);
  image.at(2, 0) = Rgb(0.3f);
  const auto out = luxel::toneMap(image, fixedExposure(ToneMap::Curve::Clamp, 1.0f));
  EXPECT_NEAR(out[0].x, srgb(0.5), 1e-6);
  EXPECT_NEAR(out[0].y, 1.0, 1e-6);
  EXPECT_EQ(out[0].z, 0.0f);
  EXPECT_NEAR(out[1].x, 1.0, 1e-6);  // 0.5 * 2^1
  EXPECT_NEAR(out[2].y, srgb(0.6), 1e-6);
}

TEST(ToneMap, ReinhardClosedForm) {
  Image image(2, 1);
  image.at(0, 0) = Rgb(3.0f);
  image.at(1, 0) = Rgb(0.5f, 0.25f, 0.1f);
  const auto out = luxel::toneMap(image, fixedExposure(ToneMap::Curve::Reinhard));
  // Grey: L / (1 + L).
  EXPECT_NEAR(out[0].x, srgb(3.0 / 4.0), 1e-6);
  EXPECT_NEAR(out[0].z, srgb(3.0 / 4.0), 1e-6);
  // Colour: RGB scaled by 1 / (1 + L), keeping the ratios.
  const double scale = 1.0 / (1.0 + rec709Luminance(0.5, 0.25, 0.1));
  EXPECT_NEAR(out[1].x, srgb(0.5 * scale), 1e-6);
  EXPECT_NEAR(out[1].y, srgb(0.25 * scale), 1e-6);
  EXPECT_NEAR(out[1].z, srgb(0.1 * scale), 1e-6);

  // Two stops up: 3 * 4 = 12 -> 12/13.
  const auto brighter = luxel::toneMap(image, fixedExposure(ToneMap::Curve::Reinhard, 2.0f));
  EXPECT_NEAR(brighter[0].y, srgb(12.0 / 13.0), 1e-6);
}

TEST(ToneMap, FilmicClosedForm) {
  const auto out = luxel::toneMap(constantImage(1, 1, Rgb(1.0f)),
                                  fixedExposure(ToneMap::Curve::Filmic));
  EXPECT_NEAR(out[0].x, srgb(2.54 / 3.16), 1e-6);
  // Far above white the curve saturates at 1, not at its asymptote 2.51/2.43.
  const auto bright = luxel::toneMap(constantImage(1, 1, Rgb(1e9f)),
                                     fixedExposure(ToneMap::Curve::Filmic));
  EXPECT_NEAR(bright[0].x, 1.0, 1e-6);
}

TEST(ToneMap, AutoExposureMapsConstantImageToMiddleGrey) {
  const double radiance = 2.5;
  const Image image = constantImage(8, 4, Rgb(float(radiance)));
  // Log-average with Reinhard's delta = 1e-4 x mean luminance: exp(log(L + delta)) = L (1 + 1e-4).
  const double logAverage = radiance * (1.0 + 1e-4);
  const double exposed = radiance * 0.18 / logAverage;  // ~0.18

  ToneMap options;  // filmic, auto exposure, 0 stops
  const auto out = luxel::toneMap(image, options);
  EXPECT_NEAR(out[0].x, srgb(aces(exposed)), 1e-6);
  EXPECT_NEAR(out[31].z, srgb(aces(exposed)), 1e-6);

  options.exposure = -1.0f;  // one stop down on top of the automatic exposure
  EXPECT_NEAR(luxel::toneMap(image, options)[5].y, srgb(aces(exposed / 2.0)), 1e-6);

  options.curve = ToneMap::Curve::Clamp;
  options.exposure = 0.0f;
  EXPECT_NEAR(luxel::toneMap(image, options)[0].x, srgb(exposed), 1e-6);
}

TEST(ToneMap, AutoExposureIgnoresUnitsAndNonFinitePixels) {
  Image image(3, 2);
  const float values[] = {0.0f, 0.02f, 0.5f, 1.0f, 4.0f, 40.0f};
  for (int i = 0; i < 6; ++i) image.pixels[i] = Rgb(values[i], values[i] * 0.5f, values[i] * 2.0f);
  const ToneMap options;
  const auto reference = luxel::toneMap(image, options);

  // The same scene in other units (x1000) gets the same picture.
  Image scaled = image;
  for (Rgb& p : scaled.pixels) p *= 1000.0f;
  const auto same = luxel::toneMap(scaled, options);
  for (size_t i = 0; i < reference.size(); ++i) EXPECT_NEAR(same[i].y, reference[i].y, 1e-5);

  // NaN and infinite pixels do not shift the exposure of the others.
  Image broken(5, 2);
  for (int i = 0; i < 6; ++i) broken.pixels[i] = image.pixels[i];
  broken.pixels[6] = Rgb(std::nanf(""));
  broken.pixels[7] = Rgb(std::numeric_limits<float>::infinity());
  broken.pixels[8] = Rgb(-std::numeric_limits<float>::infinity());
  broken.pixels[9] = Rgb(1.0f, std::nanf(""), 1.0f);
  // Only 6 finite pixels out of 10: compare against the finite ones alone.
  const auto withBroken = luxel::toneMap(broken, options);
  for (size_t i = 0; i < 6; ++i) EXPECT_NEAR(withBroken[i].x, reference[i].x, 1e-6);
  for (const Rgb& p : withBroken) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(p[c]));
      EXPECT_GE(p[c], 0.0f);
      EXPECT_LE(p[c], 1.0f);
    }
  }
}

// Metering by coverage: pixels that showed no surface (coverage 0) do not count, a half-covered
// pixel counts half, and without any coverage every pixel counts (as for an image read from EXR).
TEST(ToneMap, AutoExposureMetersOnCoveredPixels) {
  Image image(4, 1);
  image.pixels = {Rgb(2.0f), Rgb(0.5f), Rgb(0.0f), Rgb(0.0f)};  // two surfaces, two background
  image.coverage = {1.0f, 0.5f, 0.0f, 0.0f};
  // Weighted log-average, with Reinhard's delta at 1e-4 of the weighted mean luminance.
  const double mean = (2.0 + 0.5 * 0.5) / 1.5, delta = 1e-4 * mean;
  const double logAverage = std::exp((std::log(2.0 + delta) + 0.5 * std::log(0.5 + delta)) / 1.5);
  EXPECT_NEAR(luxel::autoExposureScale(image), 0.18 / logAverage, 1e-6);
  // The PNG path uses it: the brightest pixel under the clamp curve.
  ToneMap options;
  options.curve = ToneMap::Curve::Clamp;
  EXPECT_NEAR(luxel::toneMap(image, options)[0].x, srgb(std::min(1.0, 2.0 * 0.18 / logAverage)), 1e-6);

  // More background changes nothing.
  Image wider(8, 1);
  wider.pixels = image.pixels;
  wider.pixels.resize(8, Rgb(0.0f));
  wider.coverage = image.coverage;
  wider.coverage.resize(8, 0.0f);
  EXPECT_NEAR(luxel::autoExposureScale(wider), luxel::autoExposureScale(image), 1e-9);

  // Nothing covered (a view of the sky), or no coverage at all: every pixel counts alike.
  Image sky = constantImage(2, 2, Rgb(3.0f));
  EXPECT_NEAR(luxel::autoExposureScale(sky), 0.18 / (3.0 * (1.0 + 1e-4)), 1e-6);
  sky.coverage.assign(4, 0.0f);
  EXPECT_NEAR(luxel::autoExposureScale(sky), 0.18 / (3.0 * (1.0 + 1e-4)), 1e-6);

  // Coverage that is not one value per pixel is a caller's mistake, named.
  image.coverage.pop_back();
  EXPECT_NE(errorMessage([&] { luxel::autoExposureScale(image); }).find("3 coverage values for 4 pixels"),
            std::string::npos);
}

TEST(ToneMap, BlackImageStaysBlack) {
  const auto out = luxel::toneMap(constantImage(2, 2, Rgb(0.0f)), ToneMap{});
  for (const Rgb& p : out) EXPECT_EQ(p.x, 0.0f);
}

// ---- PNG and writeImage ------------------------------------------------------------------------

struct Loaded {
  int width = 0, height = 0, channels = 0;
  std::vector<unsigned char> bytes;
};

Loaded loadPng(const fs::path& path) {
  Loaded result;
  unsigned char* data = stbi_load(path.c_str(), &result.width, &result.height, &result.channels, 0);
  if (!data) {
    ADD_FAILURE() << "stbi_load failed on " << path;
    return result;
  }
  result.bytes.assign(data, data + result.width * result.height * result.channels);
  stbi_image_free(data);
  return result;
}

int expectedByte(double linear) {
  return int(std::lround(srgb(std::clamp(linear, 0.0, 1.0)) * 255.0));
}

TEST(Png, WritesExpectedEightBitValues) {
  const fs::path path = scratchDir() / "known.png";
  Image image(3, 2);
  image.at(0, 0) = Rgb(0.0f, 0.5f, 1.0f);
  image.at(1, 0) = Rgb(0.2f, 0.05f, 0.001f);
  image.at(2, 0) = Rgb(2.0f, -1.0f, 0.75f);
  image.at(0, 1) = Rgb(1.0f, 0.0f, 0.0f);  // the bottom row starts red...
  image.at(1, 1) = Rgb(0.0f, 1.0f, 0.0f);
  image.at(2, 1) = Rgb(0.0f, 0.0f, 1.0f);  // ...and ends blue
  luxel::writePng(image, path, fixedExposure(ToneMap::Curve::Clamp));

  const Loaded png = loadPng(path);
  ASSERT_EQ(png.width, 3);
  ASSERT_EQ(png.height, 2);
  ASSERT_EQ(png.channels, 3);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(int(png.bytes[size_t((y * 3 + x) * 3 + c)]), expectedByte(image.at(x, y)[c]))
            << "x " << x << " y " << y << " c " << c;
      }
    }
  }
  EXPECT_EQ(int(png.bytes[0 * 3 + 1]), 188);  // 0.5 -> sRGB 0.73536 -> 187.5 -> 188
  EXPECT_EQ(int(png.bytes[(1 * 3 + 0) * 3 + 0]), 255);
  EXPECT_EQ(listDir(path.parent_path()), std::vector<std::string>{"known.png"});
}

TEST(Png, NanAndInfinitePixelsDoNotCrash) {
  const fs::path path = scratchDir() / "nan.png";
  Image image(4, 1);
  image.at(0, 0) = Rgb(std::nanf(""));
  image.at(1, 0) = Rgb(std::numeric_limits<float>::infinity());
  image.at(2, 0) = Rgb(-std::numeric_limits<float>::infinity());
  image.at(3, 0) = Rgb(0.5f);
  luxel::writePng(image, path, ToneMap{});  // filmic with auto exposure
  const Loaded png = loadPng(path);
  ASSERT_EQ(png.bytes.size(), 12u);
  EXPECT_EQ(int(png.bytes[0]), 0);    // NaN -> black
  EXPECT_EQ(int(png.bytes[3]), 255);  // +inf -> white
  EXPECT_EQ(int(png.bytes[6]), 0);    // -inf -> black
  EXPECT_GT(int(png.bytes[9]), 0);    // the finite pixel is exposed normally
  EXPECT_LT(int(png.bytes[9]), 255);
}

TEST(WriteImage, MissingDirectoryThrowsAndLeavesNothing) {
  const fs::path dir = scratchDir();
  for (const char* name : {"out.png", "out.exr"}) {
    const fs::path path = dir / "missing" / name;
    const std::string message =
        errorMessage([&] { luxel::writeImage(constantImage(2, 2, Rgb(1.0f)), path, ToneMap{}); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("missing"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(dir / "missing"));  // never created
  EXPECT_TRUE(listDir(dir).empty());
}

TEST(WriteImage, UnknownExtensionThrows) {
  const fs::path dir = scratchDir();
  for (const char* name : {"out.jpg", "out"}) {
    const fs::path path = dir / name;
    const std::string message =
        errorMessage([&] { luxel::writeImage(constantImage(2, 2, Rgb(1.0f)), path, ToneMap{}); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(".exr"), std::string::npos) << message;
    EXPECT_NE(message.find(".png"), std::string::npos) << message;
  }
  EXPECT_TRUE(listDir(dir).empty());
}

TEST(WriteImage, ChoosesByExtensionIgnoringCase) {
  const fs::path dir = scratchDir();
  const Image image = constantImage(2, 2, Rgb(0.25f));
  luxel::writeImage(image, dir / "a.EXR", ToneMap{});
  luxel::writeImage(image, dir / "b.Png", ToneMap{});
  EXPECT_EQ(luxel::readExr(dir / "a.EXR").at(1, 1).y, 0.25f);
  EXPECT_EQ(loadPng(dir / "b.Png").channels, 3);
  EXPECT_EQ(listDir(dir).size(), 2u);
}

// ---- atomic replacement ------------------------------------------------------------------------

TEST(AtomicFile, FailedWriteKeepsOldFileAndRemovesTemporary) {
  const fs::path dir = scratchDir();
  const fs::path path = dir / "keep.txt";
  std::ofstream(path) << "old";

  const std::string message = errorMessage([&] {
    luxel::writeFileAtomically(path, [](const fs::path& tmp) {
      std::ofstream(tmp) << "half-writ";
      throw std::runtime_error("disk full");
    });
  });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("disk full"), std::string::npos) << message;
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"keep.txt"});
  std::ifstream in(path);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "old");
}

TEST(AtomicFile, ReplacesExistingFileWithTemporaryBesideIt) {
  const fs::path dir = scratchDir();
  const fs::path path = dir / "new.txt";
  std::ofstream(path) << "old";
  fs::path used;
  luxel::writeFileAtomically(path, [&](const fs::path& tmp) {
    used = tmp;
    std::ofstream(tmp) << "new";
  });
  EXPECT_EQ(used.parent_path(), dir);  // same directory, so rename is atomic
  EXPECT_NE(used.filename(), path.filename());
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"new.txt"});
  std::ifstream in(path);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "new");
}

// What a SIGTERM handler calls before the process ends: the temporary file being written goes.
TEST(AtomicFile, ASignalHandlerCanRemoveTheTemporaryBeingWritten) {
  const fs::path dir = scratchDir();
  const fs::path path = dir / "big.exr";
  bool existed = false, removed = false;
  luxel::writeFileAtomically(path, [&](const fs::path& tmp) {
    luxel::OutputFile out(tmp);
    out.write("partial");
    out.close();
    existed = fs::exists(tmp);
    luxel::removeTemporaryFilesNow();
    removed = !fs::exists(tmp);
    std::ofstream(tmp) << "whole";  // the handler would end the process here; this run goes on
  });
  EXPECT_TRUE(existed);
  EXPECT_TRUE(removed);
  // Once installed, the output is no longer a temporary: a later signal leaves it.
  luxel::removeTemporaryFilesNow();
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"big.exr"});
}

// A write the file system refuses (the file size limit here, as a full disk would) is an error,
// where a stream or stb's writer would report success with a short file.
TEST(AtomicFile, OutputFileReportsAShortWrite) {
  const fs::path dir = scratchDir();
  luxel::OutputFile out(dir / "f");
  std::string big(1 << 20, 'x');
  out.write(big);
  EXPECT_NO_THROW(out.close());
  luxel::OutputFile full("/dev/full");
  EXPECT_THROW(
      {
        full.write(big);
        full.close();
      },
      luxel::Error);
}

TEST(AtomicFile, FailedRenameRemovesTemporary) {
  const fs::path dir = scratchDir();
  const fs::path path = dir / "taken.png";
  fs::create_directory(path);  // a file cannot be renamed over a directory
  const std::string message = errorMessage(
      [&] { luxel::writePng(constantImage(2, 2, Rgb(1.0f)), path, ToneMap{}); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"taken.png"});
  EXPECT_TRUE(fs::is_directory(path));
}

}  // namespace
