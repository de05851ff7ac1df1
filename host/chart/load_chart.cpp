#include "host/chart/load_chart.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace raycube::host {
namespace {

void requireSameNonEmpty(std::size_t a, std::size_t b, const char* who) {
  if (a == 0 || b == 0) throw std::invalid_argument(std::string(who) + ": series must not be empty");
  if (a != b) {
    throw std::invalid_argument(std::string(who) + ": series differ in length (" + std::to_string(a) +
                                " and " + std::to_string(b) + ")");
  }
}

void requireCounts(std::span<const double> values, const char* series) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || values[i] < 0) {
      throw std::invalid_argument(std::string("loadChart: ") + series + " count of processor " +
                                  std::to_string(i) + " is " + std::to_string(values[i]) +
                                  "; counts must be finite and >= 0");
    }
  }
}

}  // namespace

std::vector<double> normalisedToMean(std::span<const double> values) {
  double mean = 0;
  for (double v : values) mean += v;
  mean = values.empty() ? 0 : mean / double(values.size());
  std::vector<double> normalised(values.begin(), values.end());
  if (mean > 0)
    for (double& v : normalised) v /= mean;
  return normalised;
}

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

BarChart loadChart(std::span<const double> estimated, std::span<const double> actual, std::string caption) {
  requireSameNonEmpty(estimated.size(), actual.size(), "loadChart");
  BarChart chart;
  chart.title = "Figure 15: estimated against actual load per processor";
  chart.caption = std::move(caption);
  chart.x.label = "processor";
  chart.y.label = "load / mean load (1 = the average processor)";
  for (std::size_t p = 0; p < estimated.size(); ++p) chart.categories.push_back(std::to_string(p));
  requireCounts(estimated, "estimated");
  requireCounts(actual, "actual");
  chart.series.push_back({"estimated (sub-sampled rays)", normalisedToMean(estimated)});
  chart.series.push_back({"actual (rays processed)", normalisedToMean(actual)});
  return chart;
}

}  // namespace raycube::host
