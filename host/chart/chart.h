#pragma once
// Charts as data in, picture out. A chart is a small description (title, axes with units, named series, a
// caption saying which scene and settings the numbers came from) that draws itself on a Painter. The
// renderers know nothing of charts: callers turn their reports into one of the chart types below.
//
// To add a chart: derive from Chart, hold your data in it and implement drawBody() with the helpers at the
// bottom of this header (drawAxes, drawLegend, drawColorScale) and the Painter's primitives. Title, caption,
// PNG (Cairo) and SVG come for free; nothing in chart_painter.cpp changes.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace raycube::host {

// A display colour, sRGB components in [0, 1]: charts are for eyes, not for light transport.
struct ChartColor {
  double r = 0, g = 0, b = 0;
  bool operator==(const ChartColor&) const = default;
};
inline constexpr ChartColor kChartBlack{0, 0, 0};
inline constexpr ChartColor kChartWhite{1, 1, 1};
// Okabe & Ito's qualitative palette (distinguishable with the common colour-vision deficiencies); series
// take its colours in order, wrapping after eight.
ChartColor paletteColor(std::size_t index);
// A perceptually ordered scale (viridis, sampled) for values in [0, 1]: the overlay's load colours.
ChartColor scaleColor(double fraction);

enum class TextAnchor : std::uint8_t { Start, Middle, End };
struct TextStyle {
  double size = 12;  // pixels
  TextAnchor anchor = TextAnchor::Start;
  bool bold = false;
  bool vertical = false;  // rotated a quarter turn anticlockwise, for a y-axis label
  ChartColor color = kChartBlack;
};

using ChartPoint = std::pair<double, double>;

// What a chart draws with. Device units are pixels of the PNG (user units of the SVG), y pointing down.
class Painter {
 public:
  virtual ~Painter() = default;
  virtual void fillRect(double x, double y, double w, double h, ChartColor fill, double opacity = 1) = 0;
  virtual void strokeRect(double x, double y, double w, double h, ChartColor stroke, double width) = 0;
  virtual void polyline(const std::vector<ChartPoint>& points, ChartColor stroke, double width,
                        bool dashed = false) = 0;
  virtual void disc(double x, double y, double radius, ChartColor fill) = 0;
  // (x, y) is the start, middle or end of the baseline, after the anchor.
  virtual void text(double x, double y, const std::string& text, const TextStyle& style) = 0;
  // The picture scaled to the rectangle, sRGB-encoded from its linear values.
  virtual void image(double x, double y, double w, double h, const core::Image& image) = 0;
};

// Advance width of a line of text in DejaVu Sans, measured with Cairo, so both formats lay out alike.
double textWidth(const std::string& text, double size, bool bold = false);

struct ChartRect {
  double x = 0, y = 0, w = 0, h = 0;
};

class Chart {
 public:
  std::string title;
  std::string caption;  // the scene and settings the chart came from, one line under the picture
  double preferredWidth = 760, preferredHeight = 460;  // pixels; some charts grow with their data

  virtual ~Chart() = default;
  virtual double width() const { return preferredWidth; }
  virtual double height() const { return preferredHeight; }
  // Everything but the title and caption, inside `area`.
  virtual void drawBody(Painter& painter, ChartRect area) const = 0;
  // Background, title on top, caption at the bottom, the body between.
  void draw(Painter& painter) const;
};

// ---- The chart types ----

enum class AxisScale : std::uint8_t { Linear, Log };
struct Axis {
  std::string label{};  // with its unit: "time (s)"
  AxisScale scale = AxisScale::Linear;
  std::optional<double> min{}, max{};  // default: the data's range (linear axes include 0 for counts)
  bool includeZero = false;            // linear axes: stretch the range to 0
};

struct Series {
  std::string name{};
  std::vector<double> x{}, y{};
  std::vector<std::string> pointLabels{};  // empty, or one per point (drawn beside it)
};

// Named polylines with markers on x/y axes, either of them logarithmic: the speed/accuracy trade-off, the
// scaling plot (processors against speedup or efficiency).
class LineChart : public Chart {
 public:
  Axis x, y;
  std::vector<Series> series;
  void drawBody(Painter& painter, ChartRect area) const override;
};

struct BarSeries {
  std::string name{};
  std::vector<double> values{};  // one per category, finite and >= 0
};

// Groups of bars, one group per category (figure 15: one per processor), one bar per series.
class BarChart : public Chart {
 public:
  Axis x, y;
  std::vector<std::string> categories;
  std::vector<BarSeries> series;
  double width() const override;
  void drawBody(Painter& painter, ChartRect area) const override;
};

struct TimelineInterval {
  double start = 0, end = 0;
  std::size_t state = 0;  // index into TimelineChart::states
};
struct TimelineRow {
  std::string name{};  // "P3"
  std::vector<TimelineInterval> intervals{};
};

// One row per processor over time, intervals coloured by named state (computing, forwarding, blocked,
// idle): the simulated-time timeline.
class TimelineChart : public Chart {
 public:
  Axis time;
  std::string rowLabel = "processor";
  std::vector<std::string> states;
  std::vector<ChartColor> stateColors;  // empty: the palette
  std::vector<TimelineRow> rows;
  double height() const override;
  void drawBody(Painter& painter, ChartRect area) const override;
};

struct ImageRegion {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixels of the image, half-open
  std::string label{};                 // written in the region: the processor number
  double value = 0;                    // coloured on the scale
};

// The rendered picture with annotated regions: each region's border in the colour of its value on a
// colour scale drawn beside the picture, its label in its middle, and the scale named.
class ImageChart : public Chart {
 public:
  core::Image image;
  std::vector<ImageRegion> regions;
  std::string scaleLabel;  // what the colours measure, with unit
  std::string legendNote;  // a line above the scale: the partition's name
  double width() const override;
  double height() const override;
  void drawBody(Painter& painter, ChartRect area) const override;
};

// ---- Output ----

// A standalone SVG file (with its XML namespace).
std::string chartSvg(const Chart& chart);
// The same <svg> element for inlining in HTML, where the namespace is implied: it holds no URL.
std::string chartSvgInline(const Chart& chart);
std::vector<unsigned char> chartPng(const Chart& chart);
// .png or .svg by extension (case-insensitive); creates no directories. Throws std::invalid_argument for
// another extension and std::runtime_error when the file cannot be written.
void writeChart(const Chart& chart, const std::filesystem::path& path);
// The chart rasterised, as an image in linear values (what tests inspect pixel by pixel).
core::Image chartImage(const Chart& chart);

// 8-bit sRGB PNG of an image, in memory (for data: URIs).
std::vector<unsigned char> pngBytes(const core::Image& image);
std::string base64(std::span<const unsigned char> bytes);
// & < > " as entities: text safe inside SVG or HTML elements and attribute values.
std::string markupEscaped(const std::string& text);
std::string pngDataUri(std::span<const unsigned char> png);

// ---- Helpers for drawBody ----

struct AxisRange {
  double lo = 0, hi = 1;
};
// The range an axis shows for these values: its min/max when set, else the data's, widened to nice ends.
AxisRange axisRange(const Axis& axis, std::span<const double> values);

struct Ticks {
  std::vector<double> at;
  std::vector<std::string> labels;
};
// Round values (1, 2, 5 times a power of ten; decades on a log axis) inside the range, labelled.
Ticks ticksFor(const Axis& axis, AxisRange range);

// A plot area whose axes have been drawn: maps data to device coordinates.
class PlotFrame {
 public:
  PlotFrame(ChartRect area, const Axis& x, AxisRange xRange, const Axis& y, AxisRange yRange);
  double x(double value) const;
  double y(double value) const;
  const ChartRect& area() const { return area_; }

 private:
  static double fraction(double value, AxisScale scale, AxisRange range);
  ChartRect area_;
  AxisScale xScale_, yScale_;
  AxisRange xRange_, yRange_;
};

// Draws the grid, the axes, their ticks (ticksFor, unless given) and labels inside `area`, and returns
// the frame of the plot that remains.
PlotFrame drawAxes(Painter& painter, ChartRect area, const Axis& x, AxisRange xRange, const Axis& y,
                   AxisRange yRange, const std::optional<Ticks>& xTicks = std::nullopt,
                   const std::optional<Ticks>& yTicks = std::nullopt);

enum class LegendMark : std::uint8_t { Box, Line };
struct LegendEntry {
  std::string name{};
  ChartColor color{};
  LegendMark mark = LegendMark::Box;
};
// Draws the legend in a column at the right of `area` and returns the area left of it.
ChartRect drawLegend(Painter& painter, ChartRect area, const std::vector<LegendEntry>& entries,
                     const std::string& heading = "");
// A vertical colour bar for [lo, hi] in scaleColor's colours with ticks, labelled.
void drawColorScale(Painter& painter, ChartRect bar, AxisRange range, const std::string& label);

}  // namespace raycube::host
