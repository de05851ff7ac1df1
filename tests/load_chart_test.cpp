#include "host/load_chart.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

namespace raycube::host {
namespace {

int countColor(const core::Image& image, const core::Color& color, int x0 = 0, int x1 = -1) {
  if (x1 < 0) x1 = image.width;
  int count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = x0; x < x1; ++x) count += image.at(x, y) == color ? 1 : 0;
  }
  return count;
}

// The columns of each bar of `color`, left to right, found on the lowest row holding that colour (the row
// every bar stands on), so the test does not depend on the layout's margins.
std::vector<std::pair<int, int>> barColumns(const core::Image& image, const core::Color& color) {
  for (int y = image.height - 1; y >= 0; --y) {
    std::vector<std::pair<int, int>> runs;
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y) != color) continue;
      if (!runs.empty() && runs.back().second == x) {
        runs.back().second = x + 1;
      } else {
        runs.emplace_back(x, x + 1);
      }
    }
    if (!runs.empty()) return runs;
  }
  return {};
}

TEST(Pearson, IdenticalSeriesCorrelatePerfectly) {
  const std::vector<double> a{3, 1, 4, 1, 5, 9, 2, 6};
  EXPECT_DOUBLE_EQ(pearson(a, a), 1.0);
}

TEST(Pearson, NegatedSeriesAnticorrelatePerfectly) {
  const std::vector<double> a{3, 1, 4, 1, 5, 9, 2, 6};
  std::vector<double> negated;
  for (double v : a) negated.push_back(-v);
  EXPECT_DOUBLE_EQ(pearson(a, negated), -1.0);
}

TEST(Pearson, KnownPair) {
  // a = 1..5, b = 2 4 5 4 5: means 3 and 4; deviations -2 -1 0 1 2 and -2 0 1 0 1;
  // covariance sum 4 + 0 + 0 + 0 + 2 = 6, sums of squares 10 and 6: r = 6 / sqrt(60).
  const std::vector<double> a{1, 2, 3, 4, 5};
  const std::vector<double> b{2, 4, 5, 4, 5};
  EXPECT_NEAR(pearson(a, b), 6.0 / std::sqrt(60.0), 1e-12);
  EXPECT_NEAR(pearson(b, a), 0.7745966692414834, 1e-12);
}

TEST(Pearson, ScaleAndOffsetDoNotMatter) {
  const std::vector<double> a{1, 2, 3, 4, 5};
  const std::vector<double> b{2, 4, 5, 4, 5};
  std::vector<double> scaled;
  for (double v : b) scaled.push_back(1000.0 * v + 7.0);
  EXPECT_NEAR(pearson(a, scaled), pearson(a, b), 1e-12);
}

TEST(Pearson, ZeroVarianceIsZero) {
  const std::vector<double> flat{2, 2, 2, 2};
  const std::vector<double> varied{1, 2, 3, 4};
  EXPECT_EQ(pearson(flat, varied), 0.0);
  EXPECT_EQ(pearson(varied, flat), 0.0);
  EXPECT_EQ(pearson(std::vector<double>{5}, std::vector<double>{7}), 0.0);
}

TEST(Pearson, RejectsMismatchedOrEmptySeries) {
  const std::vector<double> three{1, 2, 3};
  const std::vector<double> two{1, 2};
  EXPECT_THROW(pearson(three, two), std::invalid_argument);
  EXPECT_THROW(pearson(std::vector<double>{}, std::vector<double>{}), std::invalid_argument);
}

TEST(LoadChart, WidthGrowsWithProcessors) {
  const std::vector<double> four(4, 1.0);
  const std::vector<double> sixtyFour(64, 1.0);
  const std::vector<double> twoFiftySix(256, 1.0);
  const core::Image small = loadChart(four, four);
  const core::Image medium = loadChart(sixtyFour, sixtyFour);
  const core::Image large = loadChart(twoFiftySix, twoFiftySix);
  EXPECT_GE(small.width, 480);
  EXPECT_GT(medium.width, small.width);
  EXPECT_GT(large.width, medium.width);
  EXPECT_GE(large.width, 24 * 256);
  EXPECT_EQ(small.height, medium.height);
  EXPECT_EQ(small.pixels.size(), static_cast<std::size_t>(small.width) * small.height);
}

TEST(LoadChart, ShowsBothSeriesOnWhite) {
  const std::vector<double> estimated{10, 20, 30, 25};
  const std::vector<double> actual{1200, 1900, 3100, 2400};
  const core::Image chart = loadChart(estimated, actual);
  EXPECT_GT(countColor(chart, kEstimatedBarColor), 0);
  EXPECT_GT(countColor(chart, kActualBarColor), 0);
  EXPECT_EQ(chart.at(chart.width / 2, 1), core::Color(1.0)) << "background is white";
  // One bar per processor of each colour along the baseline.
  EXPECT_EQ(barColumns(chart, kEstimatedBarColor).size(), estimated.size());
  EXPECT_EQ(barColumns(chart, kActualBarColor).size(), actual.size());
}

TEST(LoadChart, TallerEstimateMeansMoreEstimatedPixelsInThatSlot) {
  // Both series peak at processor 2 in each chart, so only processor 1's estimated bar changes.
  const std::vector<double> actual{5, 5, 8, 5};
  const std::vector<double> lower{4, 2, 8, 4};
  const std::vector<double> higher{4, 6, 8, 4};
  const core::Image a = loadChart(lower, actual);
  const core::Image b = loadChart(higher, actual);
  ASSERT_EQ(a.width, b.width);
  const auto barsA = barColumns(a, kEstimatedBarColor);
  const auto barsB = barColumns(b, kEstimatedBarColor);
  ASSERT_EQ(barsA.size(), 4u);
  ASSERT_EQ(barsA, barsB) << "same layout in both charts";
  const auto [x0, x1] = barsA[1];
  EXPECT_GT(countColor(b, kEstimatedBarColor, x0, x1), countColor(a, kEstimatedBarColor, x0, x1));
  // The peak reaches the same height in both (normalised to the maximum).
  const auto [p0, p1] = barsA[2];
  EXPECT_EQ(countColor(b, kEstimatedBarColor, p0, p1), countColor(a, kEstimatedBarColor, p0, p1));
  // And processor 1's actual bar is untouched.
  EXPECT_EQ(countColor(a, kActualBarColor), countColor(b, kActualBarColor));
}

TEST(LoadChart, ZeroLoadsDrawNoBarButDoNotFail) {
  const std::vector<double> zeros(5, 0.0);
  const std::vector<double> some{0, 1, 0, 2, 0};
  const core::Image chart = loadChart(zeros, some);
  EXPECT_EQ(barColumns(chart, kActualBarColor).size(), 2u);  // processors 1 and 3
  EXPECT_EQ(barColumns(chart, kEstimatedBarColor).size(), 1u) << "only the legend square is blue";
}

TEST(LoadChart, RejectsBadSeries) {
  const std::vector<double> three{1, 2, 3};
  const std::vector<double> two{1, 2};
  EXPECT_THROW(loadChart(three, two), std::invalid_argument);
  EXPECT_THROW(loadChart(std::vector<double>{}, std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(loadChart(std::vector<double>{1, -1}, two), std::invalid_argument);
  EXPECT_THROW(loadChart(two, std::vector<double>{1, std::nan("")}), std::invalid_argument);
}

TEST(LoadChart, WritesAsPng) {
  const std::vector<double> estimated{10, 20, 30, 25, 12, 18};
  const std::vector<double> actual{1200, 1900, 3100, 2400, 1000, 2000};
  const core::Image chart = loadChart(estimated, actual);
  const auto path = std::filesystem::temp_directory_path() /
                    ("raycube_load_chart_test_" + std::to_string(::getpid()) + ".png");
  core::writePng(chart, path);
  const core::Image back = core::readPng(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.width, chart.width);
  EXPECT_EQ(back.height, chart.height);
}

}  // namespace
}  // namespace raycube::host
