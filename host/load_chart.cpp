#include "host/load_chart.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image_drawing.h"

namespace raycube::host {
namespace {

// Layout in pixels. The margins leave room for the axis ticks (left, bottom) and the legend (top).
constexpr int kChartHeight = 320;
constexpr int kMinChartWidth = 480;
constexpr int kPixelsPerProcessor = 24;
constexpr int kLeftMargin = 32;
constexpr int kRightMargin = 16;
constexpr int kTopMargin = 32;
constexpr int kBottomMargin = 24;
constexpr int kTickLength = 4;
constexpr int kLegendSquare = 10;
constexpr int kLegendGap = 6;
// Each bar takes this share of its processor's slot, so neighbouring groups stay visibly apart; a cap
// keeps a chart of few processors from turning into two solid blocks.
constexpr double kBarShareOfSlot = 0.35;
constexpr int kMaxBarWidth = 40;
constexpr int kGridLines = 4;  // at 0.25, 0.5, 0.75 and 1 of the normalised scale

const core::Color kBackground{1.0, 1.0, 1.0};
const core::Color kAxisColor{0.0, 0.0, 0.0};
const core::Color kGridColor{0.75, 0.75, 0.75};

void requireSameNonEmpty(std::size_t a, std::size_t b, const char* who) {
  if (a == 0 || b == 0) throw std::invalid_argument(std::string(who) + ": series must not be empty");
  if (a != b) {
    throw std::invalid_argument(std::string(who) + ": series differ in length (" + std::to_string(a) +
                                " and " + std::to_string(b) + ")");
  }
}

// Each value over the series' maximum; an all-zero series stays zero rather than dividing by zero.
std::vector<double> normalisedToMax(std::span<const double> values, const char* series) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || values[i] < 0) {
      throw std::invalid_argument(std::string("loadChart: ") + series + " count of processor " +
                                  std::to_string(i) + " is " + std::to_string(values[i]) +
                                  "; counts must be finite and >= 0");
    }
  }
  const double largest = *std::max_element(values.begin(), values.end());
  std::vector<double> normalised(values.size(), 0.0);
  if (largest > 0) {
    for (std::size_t i = 0; i < values.size(); ++i) normalised[i] = values[i] / largest;
  }
  return normalised;
}

using core::fillRect;

}  // namespace

double pearson(std::span<const double> a, std::span<const double> b) {
  requireSameNonEmpty(a.size(), b.size(), "pearson");
  const auto n = static_cast<double>(a.size());
  double meanA = 0, meanB = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    meanA += a[i];
    meanB += b[i];
  }
  meanA /= n;
  meanB /= n;
  // Centred sums (two passes) rather than sum of squares minus square of sums, which cancels badly for
  // large ray counts with small spread.
  double covariance = 0, varianceA = 0, varianceB = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double da = a[i] - meanA;
    const double db = b[i] - meanB;
    covariance += da * db;
    varianceA += da * da;
    varianceB += db * db;
  }
  if (varianceA == 0 || varianceB == 0) return 0;
  return std::clamp(covariance / std::sqrt(varianceA * varianceB), -1.0, 1.0);
}

core::Image loadChart(std::span<const double> estimated, std::span<const double> actual) {
  requireSameNonEmpty(estimated.size(), actual.size(), "loadChart");
  const std::vector<double> estimatedShare = normalisedToMax(estimated, "estimated");
  const std::vector<double> actualShare = normalisedToMax(actual, "actual");
  const int processors = static_cast<int>(estimated.size());

  const int width = std::max(kMinChartWidth, kLeftMargin + kRightMargin + kPixelsPerProcessor * processors);
  core::Image chart = core::Image::filled(width, kChartHeight, kBackground);

  const int plotLeft = kLeftMargin;
  const int plotRight = width - kRightMargin;         // exclusive
  const int plotTop = kTopMargin;                     // the row of value 1
  const int baseline = kChartHeight - kBottomMargin;  // the x axis; value 0 sits just above it
  const int plotHeight = baseline - plotTop;
  const auto rowsFor = [&](double share) {
    const int rows = static_cast<int>(std::lround(share * plotHeight));
    return share > 0 ? std::max(rows, 1) : 0;  // a processor that did any work shows at least a sliver
  };

  // Grid lines first, so bars cover them; each with a tick on the y axis, as is the baseline.
  for (int line = 0; line <= kGridLines; ++line) {
    const int y = baseline - rowsFor(static_cast<double>(line) / kGridLines);
    if (line > 0) fillRect(chart, plotLeft, y, plotRight, y + 1, kGridColor);
    fillRect(chart, plotLeft - 1 - kTickLength, y, plotLeft - 1, y + 1, kAxisColor);
  }

  const double slot = static_cast<double>(plotRight - plotLeft) / processors;
  const int barWidth = std::clamp(static_cast<int>(slot * kBarShareOfSlot), 1, kMaxBarWidth);
  for (int p = 0; p < processors; ++p) {
    const int centre = plotLeft + static_cast<int>((p + 0.5) * slot);
    fillRect(chart, centre - barWidth, baseline - rowsFor(estimatedShare[p]), centre, baseline,
             kEstimatedBarColor);
    fillRect(chart, centre, baseline - rowsFor(actualShare[p]), centre + barWidth, baseline, kActualBarColor);
    fillRect(chart, centre, baseline + 1, centre + 1, baseline + 1 + kTickLength, kAxisColor);
  }

  // Axes: y along the left of the plot, x along the baseline.
  fillRect(chart, plotLeft - 1, plotTop - kTickLength, plotLeft, baseline + 1, kAxisColor);
  fillRect(chart, plotLeft - 1, baseline, plotRight, baseline + 1, kAxisColor);

  // Legend in the top-right corner: estimated, then actual, in the order of the bars in each group.
  const int legendTop = (kTopMargin - kLegendSquare) / 2;
  const int actualLeft = width - kRightMargin - kLegendSquare;
  const int estimatedLeft = actualLeft - kLegendGap - kLegendSquare;
  fillRect(chart, estimatedLeft, legendTop, estimatedLeft + kLegendSquare, legendTop + kLegendSquare,
           kEstimatedBarColor);
  fillRect(chart, actualLeft, legendTop, actualLeft + kLegendSquare, legendTop + kLegendSquare,
           kActualBarColor);
  return chart;
}

}  // namespace raycube::host
