#include "host/chart/load_chart.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

namespace raycube::host {
namespace {

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
  const BarChart small = loadChart(four, four);
  const BarChart medium = loadChart(sixtyFour, sixtyFour);
  const BarChart large = loadChart(twoFiftySix, twoFiftySix);
  EXPECT_GE(small.width(), 480);
  EXPECT_GT(medium.width(), small.width());
  EXPECT_GT(large.width(), medium.width());
  EXPECT_GE(large.width(), 24 * 256);
  EXPECT_EQ(small.height(), medium.height());
}

TEST(LoadChart, NamesProcessorsAndBothSeriesNormalisedToTheirMeans) {
  const std::vector<double> estimated{10, 20, 30, 20};
  const std::vector<double> actual{1000, 1000, 3000, 3000};
  const BarChart chart = loadChart(estimated, actual, "balls2, 128x128");
  EXPECT_EQ(chart.categories, (std::vector<std::string>{"0", "1", "2", "3"}));
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_NE(chart.series[0].name.find("estimated"), std::string::npos);
  EXPECT_NE(chart.series[1].name.find("actual"), std::string::npos);
  EXPECT_EQ(chart.series[0].values, (std::vector<double>{0.5, 1.0, 1.5, 1.0}));
  EXPECT_EQ(chart.series[1].values, (std::vector<double>{0.5, 0.5, 1.5, 1.5}));
  EXPECT_EQ(chart.x.label, "processor");
  EXPECT_NE(chart.y.label.find("mean"), std::string::npos);
  EXPECT_EQ(chart.caption, "balls2, 128x128");
  const std::string svg = chartSvg(chart);
  for (const std::string& word :
       {chart.title, chart.x.label, chart.y.label, chart.series[0].name, chart.series[1].name, chart.caption})
    EXPECT_NE(svg.find(">" + markupEscaped(word) + "</text>"), std::string::npos) << word;
}

TEST(LoadChart, TallerEstimateMeansATallerBar) {
  // Rasterised: processor 1's estimated bar holds more of the estimate's colour when its load is higher.
  const std::vector<double> actual{5, 5, 8, 5};
  const core::Image low = chartImage(loadChart(std::vector<double>{4, 2, 8, 4}, actual));
  const core::Image high = chartImage(loadChart(std::vector<double>{4, 6, 8, 4}, actual));
  ASSERT_EQ(low.width, high.width);
  const ChartColor blue = paletteColor(0);
  const core::Color linear(core::srgb8ToLinear(std::uint8_t(std::lround(blue.r * 255))),
                           core::srgb8ToLinear(std::uint8_t(std::lround(blue.g * 255))),
                           core::srgb8ToLinear(std::uint8_t(std::lround(blue.b * 255))));
  auto count = [&](const core::Image& image) {
    int n = 0;
    for (const core::Color& c : image.pixels) n += c == linear ? 1 : 0;
    return n;
  };
  EXPECT_GT(count(low), 0);
  EXPECT_LT(count(low), count(high));
}

TEST(LoadChart, ZeroLoadsDoNotFail) {
  const std::vector<double> zeros(5, 0.0);
  const std::vector<double> some{0, 1, 0, 2, 0};
  const BarChart chart = loadChart(zeros, some);
  EXPECT_EQ(chart.series[0].values, zeros);
  EXPECT_NO_THROW(chartPng(chart));
}

TEST(LoadChart, RejectsBadSeries) {
  const std::vector<double> three{1, 2, 3};
  const std::vector<double> two{1, 2};
  EXPECT_THROW(loadChart(three, two), std::invalid_argument);
  EXPECT_THROW(loadChart(std::vector<double>{}, std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(loadChart(std::vector<double>{1, -1}, two), std::invalid_argument);
  EXPECT_THROW(loadChart(two, std::vector<double>{1, std::nan("")}), std::invalid_argument);
}

TEST(LoadChart, WritesAsPngOfTheChartsSize) {
  const std::vector<double> estimated{10, 20, 30, 25, 12, 18};
  const std::vector<double> actual{1200, 1900, 3100, 2400, 1000, 2000};
  const BarChart chart = loadChart(estimated, actual);
  const auto path = std::filesystem::temp_directory_path() /
                    ("raycube_load_chart_test_" + std::to_string(::getpid()) + ".png");
  writeChart(chart, path);
  const core::Image back = core::readPng(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.width, int(chart.width()));
  EXPECT_EQ(back.height, int(chart.height()));
}

}  // namespace
}  // namespace raycube::host
