// The two backends of the chart Painter. PNG goes through Cairo (antialiased shapes, text set in DejaVu Sans
// through Cairo's toy font API, which finds the font through fontconfig). SVG is written as plain elements
// rather than through Cairo's SVG surface, because that surface turns every glyph into an outline: the words
// of a chart would vanish from the file, from a search of the report, and from a screen reader. Both
// measure text with Cairo, so they lay a chart out identically.
#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "host/chart/chart.h"

namespace raycube::host {
namespace {

constexpr const char* kFontFamily = "DejaVu Sans";

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void selectFont(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double anchorShift(TextAnchor anchor, double width) {
  switch (anchor) {
    case TextAnchor::Start:
      return 0;
    case TextAnchor::Middle:
      return -width / 2;
    case TextAnchor::End:
      return -width;
  }
  return 0;
}

// Premultiplied ARGB32 (opaque) of the linear image, sRGB-encoded as every 8-bit picture of raycube is.
SurfacePtr surfaceOf(const core::Image& image) {
  SurfacePtr surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, std::max(1, image.width), std::max(1, image.height)),
      cairo_surface_destroy);
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int y = 0; y < image.height; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + std::ptrdiff_t(y) * stride);
    for (int x = 0; x < image.width; ++x) {
      const core::Color& c = image.at(x, y);
      row[x] = 0xff000000u | std::uint32_t(core::linearToSrgb8(c.r)) << 16 |
               std::uint32_t(core::linearToSrgb8(c.g)) << 8 | std::uint32_t(core::linearToSrgb8(c.b));
    }
  }
  cairo_surface_mark_dirty(surface.get());
  return surface;
}

class CairoPainter : public Painter {
 public:
  explicit CairoPainter(cairo_t* cr) : cr_(cr) {}

  void fillRect(double x, double y, double w, double h, ChartColor fill, double opacity) override {
    cairo_set_source_rgba(cr_, fill.r, fill.g, fill.b, opacity);
    cairo_rectangle(cr_, x, y, w, h);
    cairo_fill(cr_);
  }
  void strokeRect(double x, double y, double w, double h, ChartColor stroke, double width) override {
    setStroke(stroke, width, false);
    cairo_rectangle(cr_, x, y, w, h);
    cairo_stroke(cr_);
  }
  void polyline(const std::vector<ChartPoint>& points, ChartColor stroke, double width,
                bool dashed) override {
    if (points.size() < 2) return;
    setStroke(stroke, width, dashed);
    cairo_move_to(cr_, points[0].first, points[0].second);
    for (std::size_t i = 1; i < points.size(); ++i) cairo_line_to(cr_, points[i].first, points[i].second);
    cairo_stroke(cr_);
    cairo_set_dash(cr_, nullptr, 0, 0);
  }
  void disc(double x, double y, double radius, ChartColor fill) override {
    cairo_set_source_rgb(cr_, fill.r, fill.g, fill.b);
    cairo_arc(cr_, x, y, radius, 0, 2 * M_PI);
    cairo_fill(cr_);
  }
  void text(double x, double y, const std::string& text, const TextStyle& style) override {
    selectFont(cr_, style.size, style.bold);
    cairo_text_extents_t extents;
    cairo_text_extents(cr_, text.c_str(), &extents);
    cairo_save(cr_);
    cairo_translate(cr_, x, y);
    if (style.vertical) cairo_rotate(cr_, -M_PI / 2);
    cairo_move_to(cr_, anchorShift(style.anchor, extents.x_advance), 0);
    cairo_set_source_rgb(cr_, style.color.r, style.color.g, style.color.b);
    cairo_show_text(cr_, text.c_str());
    cairo_restore(cr_);
  }
  void image(double x, double y, double w, double h, const core::Image& image) override {
    if (image.width == 0 || image.height == 0) return;
    const SurfacePtr source = surfaceOf(image);
    cairo_save(cr_);
    cairo_translate(cr_, x, y);
    cairo_scale(cr_, w / image.width, h / image.height);
    cairo_set_source_surface(cr_, source.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr_), CAIRO_FILTER_GOOD);
    cairo_paint(cr_);
    cairo_restore(cr_);
  }

 private:
  void setStroke(ChartColor c, double width, bool dashed) {
    cairo_set_source_rgb(cr_, c.r, c.g, c.b);
    cairo_set_line_width(cr_, width);
    cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
    const double dash[] = {4 * width, 3 * width};
    cairo_set_dash(cr_, dashed ? dash : nullptr, dashed ? 2 : 0, 0);
  }
  cairo_t* cr_;
};

std::string svgColor(ChartColor c) {
  auto byte = [](double v) { return int(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
  return fmt::format("#{:02x}{:02x}{:02x}", byte(c.r), byte(c.g), byte(c.b));
}

class SvgPainter : public Painter {
 public:
  void fillRect(double x, double y, double w, double h, ChartColor fill, double opacity) override {
    body_ +=
        fmt::format(R"(<rect x="{:.2f}" y="{:.2f}" width="{:.2f}" height="{:.2f}" fill="{}"{}/>)", x, y, w, h,
                    svgColor(fill), opacity < 1 ? fmt::format(R"( fill-opacity="{:.3f}")", opacity) : "");
    body_ += '\n';
  }
  void strokeRect(double x, double y, double w, double h, ChartColor stroke, double width) override {
    body_ += fmt::format(
        R"(<rect x="{:.2f}" y="{:.2f}" width="{:.2f}" height="{:.2f}" fill="none" stroke="{}" stroke-width="{:.2f}"/>)",
        x, y, w, h, svgColor(stroke), width);
    body_ += '\n';
  }
  void polyline(const std::vector<ChartPoint>& points, ChartColor stroke, double width,
                bool dashed) override {
    if (points.size() < 2) return;
    std::string coordinates;
    for (const auto& [x, y] : points) coordinates += fmt::format("{:.2f},{:.2f} ", x, y);
    body_ += fmt::format(
        R"(<polyline points="{}" fill="none" stroke="{}" stroke-width="{:.2f}" stroke-linejoin="round"{}/>)",
        coordinates, svgColor(stroke), width,
        dashed ? fmt::format(R"( stroke-dasharray="{:.1f} {:.1f}")", 4 * width, 3 * width) : "");
    body_ += '\n';
  }
  void disc(double x, double y, double radius, ChartColor fill) override {
    body_ += fmt::format(R"(<circle cx="{:.2f}" cy="{:.2f}" r="{:.2f}" fill="{}"/>)", x, y, radius,
                         svgColor(fill));
    body_ += '\n';
  }
  void text(double x, double y, const std::string& text, const TextStyle& style) override {
    static constexpr const char* kAnchors[] = {"start", "middle", "end"};
    body_ += fmt::format(
        R"(<text x="{:.2f}" y="{:.2f}" font-size="{:.1f}" text-anchor="{}" fill="{}"{}{}>{}</text>)", x, y,
        style.size, kAnchors[int(style.anchor)], svgColor(style.color),
        style.bold ? R"( font-weight="bold")" : "",
        style.vertical ? fmt::format(R"svg( transform="rotate(-90 {:.2f} {:.2f})")svg", x, y) : "",
        markupEscaped(text));
    body_ += '\n';
  }
  void image(double x, double y, double w, double h, const core::Image& image) override {
    body_ += fmt::format(
        R"(<image x="{:.2f}" y="{:.2f}" width="{:.2f}" height="{:.2f}" preserveAspectRatio="none" href="{}"/>)",
        x, y, w, h, pngDataUri(pngBytes(image)));
    body_ += '\n';
  }

  std::string document(double width, double height, const std::string& title, bool withNamespace) const {
    // The namespace only matters to a standalone file; inline in HTML it is implied, and leaving it out
    // keeps the report free of any URL.
    return fmt::format(
        R"(<svg {}width="{:.0f}" height="{:.0f}" viewBox="0 0 {:.0f} {:.0f}" font-family="{}, sans-serif" role="img">)"
        "\n<title>{}</title>\n{}</svg>\n",
        withNamespace ? R"(xmlns="http://www.w3.org/2000/svg" )" : "", width, height, width, height,
        kFontFamily, markupEscaped(title), body_);
  }

 private:
  std::string body_;
};

cairo_status_t appendBytes(void* closure, const unsigned char* data, unsigned int length) {
  auto* out = static_cast<std::vector<unsigned char>*>(closure);
  out->insert(out->end(), data, data + length);
  return CAIRO_STATUS_SUCCESS;
}

std::vector<unsigned char> encodePng(cairo_surface_t* surface) {
  std::vector<unsigned char> png;
  if (cairo_surface_write_to_png_stream(surface, appendBytes, &png) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("cairo could not encode a PNG");
  return png;
}

SurfacePtr rasterised(const Chart& chart) {
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, int(std::ceil(chart.width())),
                                                int(std::ceil(chart.height()))),
                     cairo_surface_destroy);
  ContextPtr cr(cairo_create(surface.get()), cairo_destroy);
  CairoPainter painter(cr.get());
  chart.draw(painter);
  cairo_surface_flush(surface.get());
  return surface;
}

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  out << bytes;
  if (!out) throw std::runtime_error("failed writing " + path.string());
}

}  // namespace

double textWidth(const std::string& text, double size, bool bold) {
  // One measuring context per thread: Cairo contexts must not be shared between threads.
  thread_local SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1), cairo_surface_destroy);
  thread_local ContextPtr cr(cairo_create(surface.get()), cairo_destroy);
  selectFont(cr.get(), size, bold);
  cairo_text_extents_t extents;
  cairo_text_extents(cr.get(), text.c_str(), &extents);
  return extents.x_advance;
}

std::string chartSvgFor(const Chart& chart, bool withNamespace) {
  SvgPainter painter;
  chart.draw(painter);
  return painter.document(chart.width(), chart.height(), chart.title, withNamespace);
}

std::string chartSvg(const Chart& chart) {
  return chartSvgFor(chart, true);
}
std::string chartSvgInline(const Chart& chart) {
  return chartSvgFor(chart, false);
}

std::vector<unsigned char> chartPng(const Chart& chart) {
  return encodePng(rasterised(chart).get());
}

core::Image chartImage(const Chart& chart) {
  const SurfacePtr surface = rasterised(chart);
  const int width = cairo_image_surface_get_width(surface.get());
  const int height = cairo_image_surface_get_height(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  core::Image image = core::Image::filled(width, height);
  for (int y = 0; y < height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + std::ptrdiff_t(y) * stride);
    for (int x = 0; x < width; ++x)
      image.at(x, y) = core::Color(core::srgb8ToLinear(std::uint8_t(row[x] >> 16)),
                                   core::srgb8ToLinear(std::uint8_t(row[x] >> 8)),
                                   core::srgb8ToLinear(std::uint8_t(row[x])));
  }
  return image;
}

void writeChart(const Chart& chart, const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".svg") return writeBytes(path, chartSvg(chart));
  if (ext == ".png") {
    const std::vector<unsigned char> png = chartPng(chart);
    return writeBytes(path, std::string(png.begin(), png.end()));
  }
  throw std::invalid_argument(path.string() + ": a chart is written as .png or .svg");
}

std::vector<unsigned char> pngBytes(const core::Image& image) {
  return encodePng(surfaceOf(image).get());
}

std::string base64(std::span<const unsigned char> bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = std::uint32_t(bytes[i]) << 16;
    if (n > 1) group |= std::uint32_t(bytes[i + 1]) << 8;
    if (n > 2) group |= bytes[i + 2];
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string markupEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string pngDataUri(std::span<const unsigned char> png) {
  return "data:image/png;base64," + base64(png);
}

}  // namespace raycube::host
