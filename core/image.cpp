#include "core/image.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>
#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

namespace raycube::core {

namespace {

std::size_t pixelCount(int width, int height) {
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

void checkShape(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != pixelCount(image.width, image.height)) {
    throw std::invalid_argument(
        fmt::format("cannot write '{}': image is {}x{} but holds {} pixels (expected a positive size and "
                    "width * height pixels)",
                    path.string(), image.width, image.height, image.pixels.size()));
  }
}

void checkSameSize(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) {
    throw std::invalid_argument(fmt::format("cannot compare images of different sizes: {}x{} and {}x{}",
                                            a.width, a.height, b.width, b.height));
  }
}

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string errnoMessage(int error) {
  return std::strerror(error);
}

// ---- PNG -------------------------------------------------------------------------------------------------
// libpng reports errors by longjmp. The functions that call setjmp hold only trivially destructible locals,
// so the jump skips no destructor; the C++ callers turn the recorded message into an exception.

struct PngError {
  char message[512] = {};
};

[[noreturn]] void pngErrorHandler(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  if (error != nullptr) std::snprintf(error->message, sizeof error->message, "%s", message);
  png_longjmp(png, 1);
}

void pngWarningHandler(png_structp, png_const_charp) {}  // warnings (e.g. odd chunks) do not stop a read

bool writePngRows(std::FILE* file, int width, int height, png_bytep* rows, PngError* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, pngErrorHandler, pngWarningHandler);
  if (png == nullptr) {
    std::snprintf(error->message, sizeof error->message, "out of memory creating the PNG writer");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(error->message, sizeof error->message, "out of memory creating the PNG writer");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Rows filtered by their left neighbour alone, where libpng's default tries all five filters on every row:
  // much faster on the SPD scenes' renders, for files of nearly the same size.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

// Decodes to 8-bit RGB. On success *width, *height are set and *rgb (malloc'd, 3 bytes per pixel) must be
// freed.
bool readPngRgb8(std::FILE* file, int* width, int* height, unsigned char** rgb, PngError* error) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, pngErrorHandler, pngWarningHandler);
  if (png == nullptr) {
    std::snprintf(error->message, sizeof error->message, "out of memory creating the PNG reader");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    std::snprintf(error->message, sizeof error->message, "out of memory creating the PNG reader");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, file);
  png_read_png(
      png, info,
      PNG_TRANSFORM_EXPAND | PNG_TRANSFORM_STRIP_16 | PNG_TRANSFORM_STRIP_ALPHA | PNG_TRANSFORM_GRAY_TO_RGB,
      nullptr);
  const png_uint_32 w = png_get_image_width(png, info);
  const png_uint_32 h = png_get_image_height(png, info);
  if (png_get_channels(png, info) != 3 || png_get_bit_depth(png, info) != 8 ||
      w > static_cast<png_uint_32>(std::numeric_limits<int>::max()) ||
      h > static_cast<png_uint_32>(std::numeric_limits<int>::max())) {
    std::snprintf(error->message, sizeof error->message,
                  "unsupported PNG layout after conversion to 8-bit RGB");
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_bytepp rows = png_get_rows(png, info);
  const std::size_t rowBytes = static_cast<std::size_t>(w) * 3;
  *rgb = static_cast<unsigned char*>(std::malloc(rowBytes * h));
  if (*rgb == nullptr) {
    std::snprintf(error->message, sizeof error->message, "out of memory for a %ux%u image", w, h);
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  for (png_uint_32 y = 0; y < h; ++y) std::memcpy(*rgb + y * rowBytes, rows[y], rowBytes);
  *width = static_cast<int>(w);
  *height = static_cast<int>(h);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

// ---- Image -----------------------------------------------------------------------------------------------

Image Image::filled(int width, int height, Color fill) {
  if (width < 0 || height < 0) {
    throw std::invalid_argument(fmt::format("image size must not be negative, got {}x{}", width, height));
  }
  return Image{width, height, std::vector<Color>(pixelCount(width, height), fill)};
}

Color& Image::at(int x, int y) {
  return const_cast<Color&>(static_cast<const Image&>(*this).at(x, y));
}

const Color& Image::at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width || y >= height) {
    throw std::out_of_range(fmt::format("pixel ({}, {}) is outside the {}x{} image", x, y, width, height));
  }
  return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
}

// ---- sRGB ------------------------------------------------------------------------------------------------

std::uint8_t linearToSrgb8(double linear) {
  if (!(linear > 0.0)) return 0;  // also catches NaN
  if (linear >= 1.0) return 255;
  const double encoded = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(encoded * 255.0));
}

double srgb8ToLinear(std::uint8_t code) {
  const double encoded = code / 255.0;
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// ---- OpenEXR ---------------------------------------------------------------------------------------------

namespace {

// OpenEXR compresses and decompresses blocks on its global thread pool, empty unless asked for.
void useEveryCoreForOpenExr() {
  static const bool once = [] {
    Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency())));
    return true;
  }();
  (void)once;
}

}  // namespace

void writeExr(const Image& image, const std::filesystem::path& path) {
  checkShape(image, path);
  std::vector<float> rgb(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    rgb[3 * i + 0] = static_cast<float>(image.pixels[i].r);
    rgb[3 * i + 1] = static_cast<float>(image.pixels[i].g);
    rgb[3 * i + 2] = static_cast<float>(image.pixels[i].b);
  }
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    // zlib's fastest level, its blocks compressed on every core: writing the EXR was a large share of a short
    // run, and the file grows only slightly; a noisy image's float data still compresses slowly.
    header.zipCompressionLevel() = 1;
    useEveryCoreForOpenExr();
    for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));

    const std::size_t xStride = 3 * sizeof(float);
    const std::size_t yStride = xStride * static_cast<std::size_t>(image.width);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("R",
                       Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + 0), xStride, yStride));
    frameBuffer.insert("G",
                       Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + 1), xStride, yStride));
    frameBuffer.insert("B",
                       Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + 2), xStride, yStride));

    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("cannot write OpenEXR image '{}': {}", path.string(), e.what()));
  }
}

Image readExr(const std::filesystem::path& path) {
  try {
    useEveryCoreForOpenExr();
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dataWindow = file.header().dataWindow();
    const int width = dataWindow.max.x - dataWindow.min.x + 1;
    const int height = dataWindow.max.y - dataWindow.min.y + 1;
    const Imf::ChannelList& channels = file.header().channels();
    if (channels.findChannel("R") == nullptr && channels.findChannel("G") == nullptr &&
        channels.findChannel("B") == nullptr) {
      throw std::runtime_error("the file has no R, G or B channel");
    }

    std::vector<float> rgb(pixelCount(width, height) * 3);
    const std::size_t xStride = 3 * sizeof(float);
    const std::size_t yStride = xStride * static_cast<std::size_t>(width);
    Imf::FrameBuffer frameBuffer;
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      // A channel the file lacks is filled with 0 (the Slice fill value).
      frameBuffer.insert(
          names[c], Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, dataWindow, xStride, yStride, 1, 1, 0.0));
    }
    file.setFrameBuffer(frameBuffer);
    file.readPixels(dataWindow.min.y, dataWindow.max.y);

    Image image = Image::filled(width, height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      image.pixels[i] = Color(rgb[3 * i + 0], rgb[3 * i + 1], rgb[3 * i + 2]);
    }
    return image;
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("cannot read OpenEXR image '{}': {}", path.string(), e.what()));
  }
}

// ---- PNG -------------------------------------------------------------------------------------------------

void writePng(const Image& image, const std::filesystem::path& path) {
  checkShape(image, path);
  const std::size_t rowBytes = static_cast<std::size_t>(image.width) * 3;
  std::vector<png_byte> bytes(rowBytes * static_cast<std::size_t>(image.height));
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    bytes[3 * i + 0] = linearToSrgb8(image.pixels[i].r);
    bytes[3 * i + 1] = linearToSrgb8(image.pixels[i].g);
    bytes[3 * i + 2] = linearToSrgb8(image.pixels[i].b);
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = bytes.data() + y * rowBytes;

  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    throw std::runtime_error(
        fmt::format("cannot open '{}' for writing: {}", path.string(), errnoMessage(errno)));
  }
  PngError error;
  const bool written = writePngRows(file, image.width, image.height, rows.data(), &error);
  const bool closed = std::fclose(file) == 0;  // a full disk may only show here
  if (!written || !closed) {
    const std::string reason = !written ? std::string(error.message) : errnoMessage(errno);
    std::error_code ignored;
    std::filesystem::remove(path, ignored);  // do not leave a truncated preview behind
    throw std::runtime_error(fmt::format("cannot write PNG image '{}': {}", path.string(), reason));
  }
}

Image readPng(const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    throw std::runtime_error(
        fmt::format("cannot open '{}' for reading: {}", path.string(), errnoMessage(errno)));
  }
  PngError error;
  int width = 0;
  int height = 0;
  unsigned char* rgb = nullptr;
  const bool read = readPngRgb8(file, &width, &height, &rgb, &error);
  std::fclose(file);
  if (!read) {
    throw std::runtime_error(fmt::format("cannot read PNG image '{}': {}", path.string(), error.message));
  }

  // Decode through a table: 256 codes, one pow each.
  double table[256];
  for (int code = 0; code < 256; ++code) table[code] = srgb8ToLinear(static_cast<std::uint8_t>(code));
  Image image;
  try {
    image = Image::filled(width, height);
  } catch (...) {
    std::free(rgb);
    throw;
  }
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = Color(table[rgb[3 * i + 0]], table[rgb[3 * i + 1]], table[rgb[3 * i + 2]]);
  }
  std::free(rgb);
  return image;
}

// ---- By extension ----------------------------------------------------------------------------------------

void writeImage(const Image& image, const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".exr") return writeExr(image, path);
  if (ext == ".png") return writePng(image, path);
  throw std::invalid_argument(
      fmt::format("cannot write '{}': unknown image extension '{}' (use .exr for linear float or .png for an "
                  "sRGB preview)",
                  path.string(), path.extension().string()));
}

Image readImage(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".exr") return readExr(path);
  if (ext == ".png") return readPng(path);
  throw std::invalid_argument(
      fmt::format("cannot read '{}': unknown image extension '{}' (supported: .exr, .png)", path.string(),
                  path.extension().string()));
}

// ---- Comparison ------------------------------------------------------------------------------------------

ImageDifference compareImages(const Image& a, const Image& b) {
  checkSameSize(a, b);
  ImageDifference difference;
  double sumSquares = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    bool over = false;
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(a.pixels[i][c] - b.pixels[i][c]);
      sumSquares += d * d;
      difference.maxAbs = std::max(difference.maxAbs, d);
      over = over || d > kOneSrgbLevel;
    }
    if (over) ++difference.pixelsOver;
  }
  const std::size_t values = a.pixels.size() * 3;
  const double mse = values == 0 ? 0.0 : sumSquares / static_cast<double>(values);
  difference.rmse = std::sqrt(mse);
  difference.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
  return difference;
}

Image differenceImage(const Image& a, const Image& b, double gain) {
  checkSameSize(a, b);
  Image d = Image::filled(a.width, a.height);
  for (std::size_t i = 0; i < a.pixels.size(); ++i) d.pixels[i] = gain * glm::abs(a.pixels[i] - b.pixels[i]);
  return d;
}

std::size_t countPixelsOver(const Image& a, const Image& b, double threshold) {
  checkSameSize(a, b);
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const Color d = a.pixels[i] - b.pixels[i];
    if (std::abs(d.r) > threshold || std::abs(d.g) > threshold || std::abs(d.b) > threshold) ++count;
  }
  return count;
}

bool bitIdentical(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         (a.pixels.empty() ||
          std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0);
}

}  // namespace raycube::core
