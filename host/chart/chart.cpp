#include "host/chart/chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace raycube::host {
namespace {

// Layout, in pixels.
constexpr double kTitleSize = 16, kCaptionSize = 11, kTickSize = 11, kLabelSize = 12, kLegendSize = 11;
constexpr double kTitleBand = 34, kCaptionBand = 24;
constexpr double kTickLength = 4, kLegendRow = 18, kLegendSwatch = 12;
constexpr double kTargetTicks = 5;  // about this many ticks on a linear axis
const ChartColor kGridColor{0.88, 0.88, 0.88};
const ChartColor kCaptionColor{0.35, 0.35, 0.35};

bool plottable(double v, AxisScale scale) {
  return std::isfinite(v) && (scale == AxisScale::Linear || v > 0);
}

// 1, 2 or 5 times a power of ten, the smallest at least `rough`.
double niceStep(double rough) {
  if (!(rough > 0) || !std::isfinite(rough)) return 1;
  const double decade = std::pow(10.0, std::floor(std::log10(rough)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= rough * (1 - 1e-9)) return m * decade;
  return 10 * decade;
}

// 1, 2 or 5 times a power of ten, the largest at most `value` (> 0).
double niceBelow(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= value * (1 + 1e-9)) return m * decade;
  return decade;
}

std::string tickLabel(double value, double step) {
  // Rounded to the step first, so 0.1 + 0.2 prints as 0.3.
  const double rounded = std::round(value / step) * step;
  return fmt::format("{:g}", std::abs(rounded) < step * 1e-9 ? 0.0 : rounded);
}

void drawXTicks(Painter& painter, const PlotFrame& frame, const Ticks& ticks) {
  const ChartRect& a = frame.area();
  // Thin the labels when they would collide (a bar chart of 256 processors).
  double widest = 0;
  for (const std::string& l : ticks.labels) widest = std::max(widest, textWidth(l, kTickSize));
  const double room = ticks.at.size() > 1 ? std::abs(frame.x(ticks.at[1]) - frame.x(ticks.at[0])) : a.w;
  const std::size_t every =
      std::max<std::size_t>(1, std::size_t(std::ceil((widest + 6) / std::max(room, 1.0))));
  for (std::size_t i = 0; i < ticks.at.size(); ++i) {
    const double x = frame.x(ticks.at[i]);
    painter.polyline({{x, a.y + a.h}, {x, a.y + a.h + kTickLength}}, kChartBlack, 1);
    if (i % every == 0)
      painter.text(x, a.y + a.h + kTickLength + kTickSize + 2, ticks.labels[i],
                   {.size = kTickSize, .anchor = TextAnchor::Middle});
  }
}

void drawYTicks(Painter& painter, const PlotFrame& frame, const Ticks& ticks) {
  const ChartRect& a = frame.area();
  for (std::size_t i = 0; i < ticks.at.size(); ++i) {
    const double y = frame.y(ticks.at[i]);
    painter.polyline({{a.x - kTickLength, y}, {a.x, y}}, kChartBlack, 1);
    painter.text(a.x - kTickLength - 3, y + kTickSize * 0.35, ticks.labels[i],
                 {.size = kTickSize, .anchor = TextAnchor::End});
  }
}

std::vector<double> collect(const std::vector<Series>& series, bool xs) {
  std::vector<double> all;
  for (const Series& s : series) all.insert(all.end(), (xs ? s.x : s.y).begin(), (xs ? s.x : s.y).end());
  return all;
}

// A darker shade of a series colour, for text drawn over white.
ChartColor darker(ChartColor c) {
  return {c.r * 0.7, c.g * 0.7, c.b * 0.7};
}

double luminance(ChartColor c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// The points of a series that the axes can show, in device coordinates, with their labels ("" if none).
std::vector<std::pair<ChartPoint, std::string>> shownPoints(const Series& s, const PlotFrame& frame,
                                                            AxisScale xs, AxisScale ys) {
  std::vector<std::pair<ChartPoint, std::string>> shown;
  for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k)
    if (plottable(s.x[k], xs) && plottable(s.y[k], ys))
      shown.push_back({{frame.x(s.x[k]), frame.y(s.y[k])}, k < s.pointLabels.size() ? s.pointLabels[k] : ""});
  return shown;
}

struct PointLabel {
  ChartPoint at;
  std::string text;
};

// Points of one series closer than this share one label ("0.05, 0.02, 0"): separate labels could not be
// read, and every setting stays named.
constexpr double kSamePlace = 6;

std::vector<PointLabel> pointLabelsOf(const Series& s, const PlotFrame& frame, AxisScale xs, AxisScale ys) {
  std::vector<PointLabel> labels;
  for (const auto& [at, text] : shownPoints(s, frame, xs, ys)) {
    if (text.empty()) continue;
    if (!labels.empty() &&
        std::hypot(at.first - labels.back().at.first, at.second - labels.back().at.second) < kSamePlace)
      labels.back().text += ", " + text;
    else
      labels.push_back({at, text});
  }
  return labels;
}

bool overlaps(const ChartRect& a, const ChartRect& b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

// Tries places around the point (right, left, above, below, then farther out) and takes the one that
// overlaps the fewest labels already placed, then the fewest markers.
void placeLabel(Painter& painter, const PointLabel& label, TextStyle style,
                const std::vector<ChartPoint>& markers, std::vector<ChartRect>& taken) {
  const double w = textWidth(label.text, style.size), h = style.size;
  struct Place {
    double dx, dy;
    TextAnchor anchor;
  };
  static constexpr Place kPlaces[] = {{6, -5, TextAnchor::Start},   {6, 13, TextAnchor::Start},
                                      {-6, -5, TextAnchor::End},    {-6, 13, TextAnchor::End},
                                      {0, -9, TextAnchor::Middle},  {0, 19, TextAnchor::Middle},
                                      {0, -22, TextAnchor::Middle}, {0, 32, TextAnchor::Middle},
                                      {10, -18, TextAnchor::Start}, {-10, 26, TextAnchor::End}};
  auto boxOf = [&](const Place& p) {
    const double shift = p.anchor == TextAnchor::End ? w : p.anchor == TextAnchor::Middle ? w / 2 : 0;
    return ChartRect{label.at.first + p.dx - shift, label.at.second + p.dy - h * 0.8, w, h};
  };
  // Labels hidden under labels cannot be read at all; a marker under a label still shows around it.
  auto cost = [&](const ChartRect& box) {
    const auto labels =
        std::count_if(taken.begin(), taken.end(), [&](const ChartRect& t) { return overlaps(box, t); });
    const auto points = std::count_if(markers.begin(), markers.end(), [&](const ChartPoint& m) {
      return overlaps(box, {m.first - 3.5, m.second - 3.5, 7, 7});
    });
    return 100 * labels + points;
  };
  const Place* chosen = &kPlaces[0];
  long best = cost(boxOf(kPlaces[0]));
  for (const Place& p : kPlaces) {
    const long c = cost(boxOf(p));
    if (c < best) {
      best = c;
      chosen = &p;
    }
  }
  taken.push_back(boxOf(*chosen));
  style.anchor = chosen->anchor;
  painter.text(label.at.first + chosen->dx, label.at.second + chosen->dy, label.text, style);
}

}  // namespace

ChartColor paletteColor(std::size_t index) {
  static constexpr std::array<ChartColor, 8> kOkabeIto{{{0.000, 0.447, 0.698},
                                                        {0.902, 0.624, 0.000},
                                                        {0.000, 0.620, 0.451},
                                                        {0.835, 0.369, 0.000},
                                                        {0.800, 0.475, 0.655},
                                                        {0.337, 0.706, 0.914},
                                                        {0.941, 0.894, 0.259},
                                                        {0.000, 0.000, 0.000}}};
  return kOkabeIto[index % kOkabeIto.size()];
}

ChartColor scaleColor(double fraction) {
  // Viridis at nine evenly spaced stops, linearly interpolated.
  static constexpr std::array<ChartColor, 9> kStops{{{0.267, 0.005, 0.329},
                                                     {0.278, 0.175, 0.483},
                                                     {0.231, 0.322, 0.546},
                                                     {0.173, 0.449, 0.558},
                                                     {0.128, 0.567, 0.551},
                                                     {0.153, 0.683, 0.502},
                                                     {0.361, 0.787, 0.388},
                                                     {0.668, 0.862, 0.196},
                                                     {0.993, 0.906, 0.144}}};
  const double t = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0) * (kStops.size() - 1);
  const std::size_t i = std::min(std::size_t(t), kStops.size() - 2);
  const double f = t - double(i);
  const ChartColor a = kStops[i], b = kStops[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

void Chart::draw(Painter& painter) const {
  painter.fillRect(0, 0, width(), height(), kChartWhite);
  painter.text(width() / 2, kTitleBand - 12, title,
               {.size = kTitleSize, .anchor = TextAnchor::Middle, .bold = true});
  // A long caption is set smaller rather than cut off at the edge.
  const double fits = kCaptionSize * (width() - 20) / std::max(1.0, textWidth(caption, kCaptionSize));
  painter.text(10, height() - 8, caption, {.size = std::min(kCaptionSize, fits), .color = kCaptionColor});
  drawBody(painter, {0, kTitleBand, width(), height() - kTitleBand - kCaptionBand});
}

AxisRange axisRange(const Axis& axis, std::span<const double> values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (plottable(v, axis.scale)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  AxisRange r;
  if (axis.scale == AxisScale::Log) {
    if (!(lo <= hi)) lo = hi = 1;
    r = {niceBelow(lo), niceStep(hi)};
    if (r.lo == r.hi) r.hi = niceStep(r.hi * 1.5);
  } else {
    if (!(lo <= hi)) lo = hi = 0;
    if (axis.includeZero) {
      lo = std::min(lo, 0.0);
      hi = std::max(hi, 0.0);
    }
    if (lo == hi) {
      lo -= lo == 0 ? 0 : std::abs(lo) * 0.5;
      hi += hi == 0 ? 1 : std::abs(hi) * 0.5;
    }
    const double step = niceStep((hi - lo) / kTargetTicks);
    r = {std::floor(lo / step + 1e-9) * step, std::ceil(hi / step - 1e-9) * step};
  }
  if (axis.min) r.lo = *axis.min;
  if (axis.max) r.hi = *axis.max;
  return r;
}

Ticks ticksFor(const Axis& axis, AxisRange range) {
  Ticks t;
  if (axis.scale == AxisScale::Log) {
    const int first = int(std::floor(std::log10(range.lo) + 1e-9)),
              last = int(std::ceil(std::log10(range.hi) - 1e-9));
    // Three decades or fewer: 2 and 5 between them too, or the axis would carry only a few numbers.
    const bool fine = last - first <= 3;
    for (int k = first; k <= last; ++k)
      for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
        const double v = m * std::pow(10.0, k);
        if (v < range.lo * (1 - 1e-9) || v > range.hi * (1 + 1e-9)) continue;
        t.at.push_back(v);
        t.labels.push_back(fmt::format("{:g}", v));
      }
    return t;
  }
  const double step = niceStep((range.hi - range.lo) / kTargetTicks);
  for (double v = std::ceil(range.lo / step - 1e-9) * step; v <= range.hi + step * 1e-9; v += step) {
    t.at.push_back(v);
    t.labels.push_back(tickLabel(v, step));
  }
  return t;
}

PlotFrame::PlotFrame(ChartRect area, const Axis& x, AxisRange xRange, const Axis& y, AxisRange yRange)
    : area_(area), xScale_(x.scale), yScale_(y.scale), xRange_(xRange), yRange_(yRange) {}

double PlotFrame::fraction(double value, AxisScale scale, AxisRange range) {
  if (scale == AxisScale::Log)
    return (std::log10(value) - std::log10(range.lo)) / (std::log10(range.hi) - std::log10(range.lo));
  return (value - range.lo) / (range.hi - range.lo);
}

double PlotFrame::x(double value) const {
  return area_.x + area_.w * fraction(value, xScale_, xRange_);
}
double PlotFrame::y(double value) const {
  return area_.y + area_.h * (1 - fraction(value, yScale_, yRange_));
}

PlotFrame drawAxes(Painter& painter, ChartRect area, const Axis& x, AxisRange xRange, const Axis& y,
                   AxisRange yRange, const std::optional<Ticks>& xTicks, const std::optional<Ticks>& yTicks) {
  const Ticks xt = xTicks ? *xTicks : ticksFor(x, xRange);
  const Ticks yt = yTicks ? *yTicks : ticksFor(y, yRange);
  double widest = 0;
  for (const std::string& l : yt.labels) widest = std::max(widest, textWidth(l, kTickSize));
  const double left = 10 + kLabelSize + 8 + widest + kTickLength + 3;
  const double bottom = kTickLength + kTickSize + 8 + kLabelSize + 8;
  const ChartRect plot{area.x + left, area.y + 8, std::max(10.0, area.w - left - 14),
                       std::max(10.0, area.h - 8 - bottom)};
  const PlotFrame frame(plot, x, xRange, y, yRange);
  for (double v : yt.at)
    painter.polyline({{plot.x, frame.y(v)}, {plot.x + plot.w, frame.y(v)}}, kGridColor, 1);
  painter.polyline({{plot.x, plot.y}, {plot.x, plot.y + plot.h}, {plot.x + plot.w, plot.y + plot.h}},
                   kChartBlack, 1.2);
  drawXTicks(painter, frame, xt);
  drawYTicks(painter, frame, yt);
  painter.text(plot.x + plot.w / 2, area.y + area.h - 6, x.label,
               {.size = kLabelSize, .anchor = TextAnchor::Middle});
  painter.text(area.x + 10 + kLabelSize, plot.y + plot.h / 2, y.label,
               {.size = kLabelSize, .anchor = TextAnchor::Middle, .vertical = true});
  return frame;
}

ChartRect drawLegend(Painter& painter, ChartRect area, const std::vector<LegendEntry>& entries,
                     const std::string& heading) {
  double widest = heading.empty() ? 0 : textWidth(heading, kLegendSize, true);
  for (const LegendEntry& e : entries)
    widest = std::max(widest, kLegendSwatch + 8 + textWidth(e.name, kLegendSize));
  const double width = widest + 24;
  const double x = area.x + area.w - width + 8;
  double y = area.y + 14;
  if (!heading.empty()) {
    painter.text(x, y + kLegendSize * 0.35, heading, {.size = kLegendSize, .bold = true});
    y += kLegendRow;
  }
  for (const LegendEntry& e : entries) {
    if (e.mark == LegendMark::Box) {
      painter.fillRect(x, y - kLegendSwatch / 2, kLegendSwatch, kLegendSwatch, e.color);
    } else {
      painter.polyline({{x, y}, {x + kLegendSwatch, y}}, e.color, 2);
      painter.disc(x + kLegendSwatch / 2, y, 3, e.color);
    }
    painter.text(x + kLegendSwatch + 6, y + kLegendSize * 0.35, e.name, {.size = kLegendSize});
    y += kLegendRow;
  }
  return {area.x, area.y, area.w - width, area.h};
}

void drawColorScale(Painter& painter, ChartRect bar, AxisRange range, const std::string& label) {
  constexpr int kSlices = 64;
  for (int i = 0; i < kSlices; ++i) {
    const double y = bar.y + bar.h * (1 - double(i + 1) / kSlices);
    painter.fillRect(bar.x, y, bar.w, bar.h / kSlices + 0.5, scaleColor((i + 0.5) / kSlices));
  }
  painter.strokeRect(bar.x, bar.y, bar.w, bar.h, kChartBlack, 1);
  const Ticks ticks = ticksFor(Axis{}, range);
  double widest = 0;
  for (std::size_t i = 0; i < ticks.at.size(); ++i) {
    const double y = bar.y + bar.h * (1 - (ticks.at[i] - range.lo) / (range.hi - range.lo));
    painter.polyline({{bar.x + bar.w, y}, {bar.x + bar.w + kTickLength, y}}, kChartBlack, 1);
    painter.text(bar.x + bar.w + kTickLength + 3, y + kTickSize * 0.35, ticks.labels[i], {.size = kTickSize});
    widest = std::max(widest, textWidth(ticks.labels[i], kTickSize));
  }
  painter.text(bar.x + bar.w + kTickLength + widest + 10 + kLabelSize, bar.y + bar.h / 2, label,
               {.size = kLabelSize, .anchor = TextAnchor::Middle, .vertical = true});
}

void LineChart::drawBody(Painter& painter, ChartRect area) const {
  std::vector<LegendEntry> legend;
  for (std::size_t i = 0; i < series.size(); ++i)
    legend.push_back({series[i].name, paletteColor(i), LegendMark::Line});
  const ChartRect rest = drawLegend(painter, area, legend);
  const std::vector<double> xs = collect(series, true), ys = collect(series, false);
  const PlotFrame frame = drawAxes(painter, rest, x, axisRange(x, xs), y, axisRange(y, ys));
  std::vector<ChartPoint> markers;
  for (std::size_t i = 0; i < series.size(); ++i) {
    std::vector<ChartPoint> points;
    for (const auto& [point, label] : shownPoints(series[i], frame, x.scale, y.scale))
      points.push_back(point);
    markers.insert(markers.end(), points.begin(), points.end());
    painter.polyline(points, paletteColor(i), 2);
    for (const ChartPoint& p : points) painter.disc(p.first, p.second, 3.5, paletteColor(i));
  }
  // Labels last, each where it overlaps no other label and no marker.
  std::vector<ChartRect> taken;
  for (std::size_t i = 0; i < series.size(); ++i)
    for (const PointLabel& label : pointLabelsOf(series[i], frame, x.scale, y.scale)) {
      const TextStyle style{.size = 10, .color = darker(paletteColor(i))};
      placeLabel(painter, label, style, markers, taken);
    }
}

double BarChart::width() const {
  return std::max(preferredWidth,
                  220 + double(categories.size()) * std::max(24.0, 10.0 * double(series.size())));
}

void BarChart::drawBody(Painter& painter, ChartRect area) const {
  std::vector<LegendEntry> legend;
  std::vector<double> values;
  for (std::size_t i = 0; i < series.size(); ++i) {
    legend.push_back({series[i].name, paletteColor(i)});
    values.insert(values.end(), series[i].values.begin(), series[i].values.end());
  }
  const ChartRect rest = drawLegend(painter, area, legend);
  Axis yAxis = y;
  yAxis.includeZero = true;
  const double n = double(categories.size());
  Ticks xt;
  for (std::size_t c = 0; c < categories.size(); ++c) {
    xt.at.push_back(double(c) + 0.5);
    xt.labels.push_back(categories[c]);
  }
  const AxisRange yr = axisRange(yAxis, values);
  const PlotFrame frame = drawAxes(painter, rest, x, {0, std::max(n, 1.0)}, yAxis, yr, xt);
  // Each group fills 80% of its slot, so neighbouring groups stay visibly apart.
  const double slot = frame.x(1) - frame.x(0),
               bar = 0.8 * slot / double(std::max<std::size_t>(1, series.size()));
  for (std::size_t s = 0; s < series.size(); ++s)
    for (std::size_t c = 0; c < std::min(categories.size(), series[s].values.size()); ++c) {
      const double v = std::clamp(series[s].values[c], yr.lo, yr.hi);
      const double left = frame.x(double(c)) + 0.1 * slot + double(s) * bar;
      painter.fillRect(left, frame.y(v), bar, frame.y(std::max(0.0, yr.lo)) - frame.y(v), paletteColor(s));
    }
}

double TimelineChart::height() const {
  return std::max(320.0, 150 + 16 * double(rows.size()));
}

void TimelineChart::drawBody(Painter& painter, ChartRect area) const {
  std::vector<LegendEntry> legend;
  auto colorOf = [&](std::size_t state) {
    return state < stateColors.size() ? stateColors[state] : paletteColor(state);
  };
  for (std::size_t s = 0; s < states.size(); ++s) legend.push_back({states[s], colorOf(s)});
  const ChartRect rest = drawLegend(painter, area, legend, "state");
  std::vector<double> times;
  for (const TimelineRow& r : rows)
    for (const TimelineInterval& i : r.intervals) times.insert(times.end(), {i.start, i.end});
  Axis timeAxis = time;
  timeAxis.includeZero = true;
  // Row 0 on top: row k occupies [n - k - 1, n - k] of the y axis.
  const double n = double(rows.size());
  Ticks yt;
  for (std::size_t k = rows.size(); k-- > 0;) {
    yt.at.push_back(n - double(k) - 0.5);
    yt.labels.push_back(rows[k].name);
  }
  Axis rowAxis;
  rowAxis.label = rowLabel;
  const PlotFrame frame = drawAxes(painter, rest, timeAxis, axisRange(timeAxis, times), rowAxis,
                                   {0, std::max(n, 1.0)}, std::nullopt, yt);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double top = frame.y(n - double(k)), bottom = frame.y(n - double(k) - 1);
    for (const TimelineInterval& i : rows[k].intervals)
      painter.fillRect(frame.x(i.start), top + 0.1 * (bottom - top), frame.x(i.end) - frame.x(i.start),
                       0.8 * (bottom - top), colorOf(i.state));
  }
}

namespace {
// The picture is shown about 512 pixels on its longer side, never magnified more than 4 times.
double displayScale(const core::Image& image) {
  const int longer = std::max({image.width, image.height, 1});
  return std::clamp(512.0 / longer, 0.05, 4.0);
}
constexpr double kScaleColumn = 190;  // room right of the picture for the colour scale and its labels
}  // namespace

double ImageChart::width() const {
  return std::max(480.0, image.width * displayScale(image) + 24 + kScaleColumn);
}
double ImageChart::height() const {
  return std::max(360.0, image.height * displayScale(image) + 16) + kTitleBand + kCaptionBand;
}

void ImageChart::drawBody(Painter& painter, ChartRect area) const {
  const double s = displayScale(image);
  const double ix = area.x + 12, iy = area.y + 4;
  painter.image(ix, iy, image.width * s, image.height * s, image);
  std::vector<double> values;
  for (const ImageRegion& r : regions) values.push_back(r.value);
  // The data's range, not from zero: the differences between processors are what the reader looks for.
  const AxisRange range = axisRange(Axis{}, values);
  for (const ImageRegion& r : regions) {
    const double x0 = ix + r.x0 * s, y0 = iy + r.y0 * s, w = (r.x1 - r.x0) * s, h = (r.y1 - r.y0) * s;
    const ChartColor c = scaleColor((r.value - range.lo) / (range.hi - range.lo));
    painter.fillRect(x0, y0, w, h, c, 0.35);
    painter.strokeRect(x0, y0, w, h, kChartWhite, 1);
    const double size = std::clamp(std::min(w, h) / 2.5, 7.0, 14.0);
    const double boxW = textWidth(r.label, size, true) + 6;
    if (boxW > w || size + 4 > h) continue;  // too small a region to write in
    painter.fillRect(x0 + w / 2 - boxW / 2, y0 + h / 2 - size * 0.6 - 2, boxW, size * 1.2 + 4, c);
    painter.text(x0 + w / 2, y0 + h / 2 + size * 0.35, r.label,
                 {.size = size,
                  .anchor = TextAnchor::Middle,
                  .bold = true,
                  .color = luminance(c) > 0.5 ? kChartBlack : kChartWhite});
  }
  const double barX = ix + image.width * s + 24;
  painter.text(barX, iy + 12, legendNote, {.size = kLegendSize, .bold = true});
  const double barTop = iy + 28;
  drawColorScale(painter, {barX, barTop, 18, std::min(300.0, std::max(120.0, image.height * s - 40))}, range,
                 scaleLabel);
}

}  // namespace raycube::host
