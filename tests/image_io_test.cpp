// core/image: EXR keeps floats exactly, PNG is an sRGB preview within one 8-bit step, failures name the path,
// and the comparison helpers that later tests rely on measure what they claim.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/image.h"
#include "test_support.h"

namespace raycube::core {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test so parallel ctest runs never share files.
class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("raycube_image_io_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

// Message of the exception `call` throws as E, or a failure when it throws nothing.
template <typename E, typename F>
std::string thrownMessage(F&& call) {
  try {
    call();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception";
  return {};
}

Image gradient(int width, int height, double scale) {
  Image image = Image::filled(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double t = (x + width * y) / static_cast<double>(width * height - 1);
      image.at(x, y) = Color(scale * t, scale * (1.0 - t), scale * t * t - 0.1);
    }
  }
  return image;
}

TEST(ImageTest, AtIsRowMajorWithTopRowFirst) {
  Image image = Image::filled(3, 2, Color(0.5));
  image.at(2, 1) = Color(1, 2, 3);
  EXPECT_EQ(image.pixels[1 * 3 + 2], Color(1, 2, 3));
  EXPECT_EQ(image.at(0, 0), Color(0.5));
  EXPECT_THROW(image.at(3, 0), std::out_of_range);
  EXPECT_THROW(image.at(0, -1), std::out_of_range);
}

TEST(SrgbTest, TransferFunctionEndpointsAndMidGrey) {
  EXPECT_EQ(linearToSrgb8(0.0), 0);
  EXPECT_EQ(linearToSrgb8(1.0), 255);
  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357, * 255 = 187.516 -> 188.
  EXPECT_EQ(linearToSrgb8(0.5), 188);
  // The linear segment: 0.002 * 12.92 * 255 = 6.59 -> 7.
  EXPECT_EQ(linearToSrgb8(0.002), 7);
  EXPECT_EQ(linearToSrgb8(-3.0), 0);
  EXPECT_EQ(linearToSrgb8(7.0), 255);
  EXPECT_EQ(linearToSrgb8(std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(srgb8ToLinear(0), 0.0);
  EXPECT_EQ(srgb8ToLinear(255), 1.0);
  EXPECT_NEAR(srgb8ToLinear(188), 0.502886, 1e-6);
}

TEST(SrgbTest, EncodingIsMonotoneAndInvertsDecoding) {
  int previous = 0;
  for (int i = 0; i <= 100000; ++i) {
    const int code = linearToSrgb8(i / 100000.0);
    ASSERT_GE(code, previous) << "at linear " << i / 100000.0;
    previous = code;
  }
  for (int code = 0; code < 256; ++code) {
    EXPECT_EQ(linearToSrgb8(srgb8ToLinear(static_cast<std::uint8_t>(code))), code);
    if (code > 0) {
      EXPECT_GT(srgb8ToLinear(static_cast<std::uint8_t>(code)),
                srgb8ToLinear(static_cast<std::uint8_t>(code - 1)));
    }
  }
}

TEST_F(ImageIoTest, ExrRoundTripIsExactForFloatValues) {
  Image image = Image::filled(5, 3);
  const float values[] = {
      0.0f,   1.0f, 0.5f,       1234.5f, 65504.0f, 1.0e6f, 1.0e-30f,  3.0e-40f /* denormal */,
      -0.25f, 0.1f, 0.7071067f, 1.0e-7f, 2.0f,     42.0f,  0.3333333f};
  std::size_t k = 0;
  for (Color& pixel : image.pixels) {
    pixel = Color(values[k % 15], values[(k + 5) % 15], values[(k + 11) % 15]);
    ++k;
  }
  const fs::path path = dir_ / "round.exr";
  writeExr(image, path);
  const Image back = readExr(path);
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  EXPECT_TRUE(bitIdentical(back, image));
}

TEST_F(ImageIoTest, ExrStoresFloatPrecisionNotHalf) {
  // 1 + 2^-20 is a float but rounds to 1 in half: a half-float writer would lose it.
  const double value = 1.0 + std::ldexp(1.0, -20);
  const Image image = Image::filled(2, 2, Color(value, 1e5, 1e-6));
  const fs::path path = dir_ / "precision.exr";
  writeExr(image, path);
  const Image back = readExr(path);
  EXPECT_EQ(back.at(1, 1).r, value);
  EXPECT_EQ(back.at(1, 1).g, 1e5);
  EXPECT_EQ(back.at(1, 1).b, static_cast<double>(1e-6f));
}

TEST_F(ImageIoTest, PngRoundTripIsWithinSrgbQuantisation) {
  const Image image = gradient(37, 23, 1.3);  // includes values above 1 and below 0, clamped by the preview
  const fs::path path = dir_ / "round.png";
  writePng(image, path);
  const Image back = readPng(path);
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 23);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double expected = srgb8ToLinear(linearToSrgb8(image.at(x, y)[c]));
        ASSERT_EQ(back.at(x, y)[c], expected) << "pixel (" << x << ", " << y << ") channel " << c;
        const double clamped = std::clamp(image.at(x, y)[c], 0.0, 1.0);
        // Half an 8-bit step in sRGB space is at most ~0.0045 in linear (near white).
        EXPECT_NEAR(back.at(x, y)[c], clamped, 0.005);
      }
    }
  }
}

TEST_F(ImageIoTest, WriteImageChoosesFormatByExtensionCaseInsensitively) {
  const Image image = gradient(4, 4, 2.0);
  writeImage(image, dir_ / "upper.EXR");
  writeImage(image, dir_ / "upper.Png");
  const Image exr = readImage(dir_ / "upper.EXR");
  ASSERT_EQ(exr.pixels.size(), image.pixels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(exr.pixels[i][c], static_cast<double>(static_cast<float>(image.pixels[i][c])))
          << i << " " << c;
    }
  }
  EXPECT_EQ(readImage(dir_ / "upper.Png").width, 4);
}

TEST_F(ImageIoTest, UnknownExtensionThrowsNamingThePath) {
  const Image image = Image::filled(2, 2);
  const std::string message =
      thrownMessage<std::invalid_argument>([&] { writeImage(image, dir_ / "picture.jpg"); });
  EXPECT_NE(message.find("picture.jpg"), std::string::npos) << message;
  EXPECT_NE(message.find(".exr"), std::string::npos) << message;
  EXPECT_THROW(writeImage(image, dir_ / "no_extension"), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "picture.jpg"));
}

TEST_F(ImageIoTest, UnwritablePathThrowsNamingThePath) {
  const Image image = Image::filled(2, 2, Color(0.5));
  // A missing parent directory fails even for root, unlike a read-only one.
  const fs::path png = dir_ / "missing_dir" / "out.png";
  const fs::path exr = dir_ / "missing_dir" / "out.exr";
  std::string message = thrownMessage<std::runtime_error>([&] { writeImage(image, png); });
  EXPECT_NE(message.find(png.string()), std::string::npos) << message;
  message = thrownMessage<std::runtime_error>([&] { writeImage(image, exr); });
  EXPECT_NE(message.find(exr.string()), std::string::npos) << message;
  // A directory in the way of the file.
  fs::create_directories(dir_ / "taken.png");
  message = thrownMessage<std::runtime_error>([&] { writePng(image, dir_ / "taken.png"); });
  EXPECT_NE(message.find("taken.png"), std::string::npos) << message;
}

TEST_F(ImageIoTest, MissingAndCorruptFilesThrowNamingThePath) {
  std::string message = thrownMessage<std::runtime_error>([&] { readPng(dir_ / "absent.png"); });
  EXPECT_NE(message.find("absent.png"), std::string::npos) << message;
  message = thrownMessage<std::runtime_error>([&] { readExr(dir_ / "absent.exr"); });
  EXPECT_NE(message.find("absent.exr"), std::string::npos) << message;

  std::ofstream(dir_ / "garbage.png") << "this is not a png file at all";
  std::ofstream(dir_ / "garbage.exr") << "this is not an exr file at all";
  message = thrownMessage<std::runtime_error>([&] { readPng(dir_ / "garbage.png"); });
  EXPECT_NE(message.find("garbage.png"), std::string::npos) << message;
  message = thrownMessage<std::runtime_error>([&] { readExr(dir_ / "garbage.exr"); });
  EXPECT_NE(message.find("garbage.exr"), std::string::npos) << message;

  // A valid PNG cut short: the header parses, the pixel data does not.
  writePng(gradient(64, 64, 1.0), dir_ / "whole.png");
  const auto size = fs::file_size(dir_ / "whole.png");
  fs::copy_file(dir_ / "whole.png", dir_ / "truncated.png");
  fs::resize_file(dir_ / "truncated.png", size / 2);
  message = thrownMessage<std::runtime_error>([&] { readPng(dir_ / "truncated.png"); });
  EXPECT_NE(message.find("truncated.png"), std::string::npos) << message;
}

TEST_F(ImageIoTest, WritingAMisshapenImageThrows) {
  Image image;
  image.width = 4;
  image.height = 4;
  image.pixels.resize(15);
  EXPECT_THROW(writePng(image, dir_ / "bad.png"), std::invalid_argument);
  EXPECT_THROW(writeExr(image, dir_ / "bad.exr"), std::invalid_argument);
}

TEST(ReferenceImageTest, PovRayReferenceReadsAs512By512) {
  const Image reference = readPng(testing_support::sourcePath("tests/data/balls2_512_povray.png"));
  EXPECT_EQ(reference.width, 512);
  EXPECT_EQ(reference.height, 512);
  ASSERT_EQ(reference.pixels.size(), 512u * 512u);
  // Not a blank image: the background and the balls differ.
  const ImageDifference fromBlack = compareImages(reference, Image::filled(512, 512));
  EXPECT_GT(fromBlack.maxAbs, 0.1);
}

TEST(CompareImagesTest, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  const Image image = gradient(8, 8, 1.0);
  const ImageDifference d = compareImages(image, image);
  EXPECT_EQ(d.rmse, 0.0);
  EXPECT_EQ(d.maxAbs, 0.0);
  EXPECT_EQ(d.pixelsOver, 0u);
  EXPECT_TRUE(std::isinf(d.psnr) && d.psnr > 0);
  EXPECT_TRUE(bitIdentical(image, image));
}

TEST(CompareImagesTest, KnownDifferenceGivesKnownNumbers) {
  const Image a = Image::filled(2, 2);
  Image b = a;
  b.at(1, 0) = Color(0.4, 0.0, 0.0);
  b.at(0, 1) = Color(0.0, 0.5 / 255.0, 0.0);  // under one sRGB level: not counted
  const ImageDifference d = compareImages(a, b);
  const double sumSquares = 0.4 * 0.4 + (0.5 / 255.0) * (0.5 / 255.0);
  EXPECT_DOUBLE_EQ(d.rmse, std::sqrt(sumSquares / 12.0));
  EXPECT_DOUBLE_EQ(d.psnr, 10.0 * std::log10(12.0 / sumSquares));
  EXPECT_DOUBLE_EQ(d.maxAbs, 0.4);
  EXPECT_EQ(d.pixelsOver, 1u);
  EXPECT_EQ(countPixelsOver(a, b, 0.0), 2u);
  EXPECT_EQ(countPixelsOver(a, b, 0.4), 0u);
  EXPECT_FALSE(bitIdentical(a, b));
}

TEST(CompareImagesTest, DifferentSizesThrow) {
  EXPECT_THROW(compareImages(Image::filled(2, 2), Image::filled(2, 3)), std::invalid_argument);
  EXPECT_THROW(countPixelsOver(Image::filled(2, 2), Image::filled(3, 2), 0.0), std::invalid_argument);
  EXPECT_FALSE(bitIdentical(Image::filled(2, 2), Image::filled(4, 1)));
}

TEST(CompareImagesTest, BitIdenticalDistinguishesSignedZero) {
  const Image positive = Image::filled(1, 1, Color(0.0));
  const Image negative = Image::filled(1, 1, Color(-0.0));
  EXPECT_FALSE(bitIdentical(positive, negative));
  EXPECT_EQ(compareImages(positive, negative).rmse, 0.0);
}

}  // namespace
}  // namespace raycube::core
