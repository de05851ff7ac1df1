#pragma once
// The rendered picture and its files: linear float OpenEXR for the result, 8-bit sRGB PNG for a preview,
// and the comparisons tests use to judge one image against another.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/vec.h"

namespace raycube::core {

// Linear radiance per pixel, row-major, y = 0 is the top row (as both EXR and PNG store them).
struct Image {
  int width = 0;
  int height = 0;
  std::vector<Color> pixels;

  // A width x height image with every pixel set to fill; throws std::invalid_argument for negative sizes.
  static Image filled(int width, int height, Color fill = Color(0.0));

  // Bounds-checked: throws std::out_of_range naming the pixel and the image size.
  Color& at(int x, int y);
  const Color& at(int x, int y) const;
};

// One 8-bit sRGB step; differences below it are invisible in the PNG preview.
inline constexpr double kOneSrgbLevel = 1.0 / 255.0;

// IEC 61966-2-1 transfer function. Input is clamped to [0, 1] (NaN maps to 0), output rounded to nearest.
std::uint8_t linearToSrgb8(double linear);
// Exact inverse of the transfer function for an 8-bit code; linearToSrgb8(srgb8ToLinear(v)) == v.
double srgb8ToLinear(std::uint8_t code);

// All writers and readers throw std::runtime_error naming the path when the file cannot be opened,
// written or decoded, and std::invalid_argument when the Image's pixel count is not width * height.
// Parent directories are not created.

// 32-bit float R, G, B channels (ZIP compression, lossless): values > 1 and tiny values survive exactly
// as far as float precision goes.
void writeExr(const Image& image, const std::filesystem::path& path);
// Reads R, G, B of any pixel type as float; a missing channel reads as 0, a file with none of them throws.
Image readExr(const std::filesystem::path& path);

// 8-bit RGB preview: linear clamped to [0, 1], sRGB-encoded, tagged with an sRGB chunk.
void writePng(const Image& image, const std::filesystem::path& path);
// Any PNG (palette, grey, 16-bit, alpha) as RGB, decoded as sRGB to linear. Alpha is dropped; a gAMA
// chunk is ignored (POV-Ray's previews are compared as if they were sRGB).
Image readPng(const std::filesystem::path& path);

// Chooses the format by extension, case-insensitive: .exr or .png. Any other extension throws
// std::invalid_argument naming the path and the supported extensions.
void writeImage(const Image& image, const std::filesystem::path& path);
Image readImage(const std::filesystem::path& path);

// Differences over all channels of all pixels of two images of the same size.
struct ImageDifference {
  double rmse = 0;             // root mean square difference over every channel value
  double psnr = 0;             // dB relative to a peak of 1.0; +infinity when the images are identical
  double maxAbs = 0;           // largest absolute difference of any single channel value
  std::size_t pixelsOver = 0;  // pixels where some channel differs by more than kOneSrgbLevel
};

// Throws std::invalid_argument when the sizes differ.
ImageDifference compareImages(const Image& a, const Image& b);
// |a - b| per channel, times gain (to make small differences visible). Throws when the sizes differ.
Image differenceImage(const Image& a, const Image& b, double gain = 1);
// Pixels where some channel differs by more than threshold. Throws std::invalid_argument when sizes differ.
std::size_t countPixelsOver(const Image& a, const Image& b, double threshold);
// Same size and the same bit pattern in every channel (so -0.0 differs from 0.0 and a NaN matches itself):
// what a deterministic renderer must reproduce run after run.
bool bitIdentical(const Image& a, const Image& b);

}  // namespace raycube::core
