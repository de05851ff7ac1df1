// Charts: every chart carries its words (title, axis labels with units, legend names, caption) as text in
// the SVG; the path's extension picks the format; ticks land on round values.
#include "host/chart/chart.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace raycube::host {
namespace {

namespace fs = std::filesystem;

bool hasText(const std::string& svg, const std::string& words) {
  return svg.find(">" + markupEscaped(words) + "</text>") != std::string::npos;
}

void expectWords(const Chart& chart, const std::vector<std::string>& words) {
  const std::string svg = chartSvg(chart);
  EXPECT_TRUE(hasText(svg, chart.title)) << "title " << chart.title;
  EXPECT_TRUE(hasText(svg, chart.caption)) << "caption " << chart.caption;
  for (const std::string& w : words) EXPECT_TRUE(hasText(svg, w)) << w;
}

LineChart scalingPlot() {
  LineChart chart;
  chart.title = "Speed-up against processors";
  chart.caption = "balls2, 512x512, machine";
  chart.x.label = "processors";
  chart.x.scale = AxisScale::Log;
  chart.y.label = "speed-up (x)";
  chart.series.push_back({"speed-up", {1, 2, 4, 8}, {1, 1.9, 3.5, 6.1}, {"1", "2", "4", "8"}});
  chart.series.push_back({"ideal", {1, 8}, {1, 8}, {}});
  return chart;
}

TEST(Chart, LineChartCarriesItsWords) {
  const LineChart chart = scalingPlot();
  expectWords(chart, {"processors", "speed-up (x)", "speed-up", "ideal", "4"});
}

TEST(Chart, BarChartCarriesItsWords) {
  BarChart chart;
  chart.title = "Rays per processor";
  chart.caption = "teapot, 256x256";
  chart.x.label = "processor";
  chart.y.label = "rays (millions)";
  chart.categories = {"0", "1", "2"};
  chart.series = {{"eye", {1, 2, 3}}, {"shadow & light", {3, 2, 1}}};
  expectWords(chart, {"processor", "rays (millions)", "eye", "shadow & light"});
}

TEST(Chart, TimelineChartCarriesStatesAndRows) {
  TimelineChart chart;
  chart.title = "Simulated time";
  chart.caption = "balls2, 4 processors, SimGrid";
  chart.time.label = "simulated time (s)";
  chart.states = {"computing", "forwarding", "blocked", "idle"};
  for (int p = 0; p < 4; ++p)
    chart.rows.push_back({"P" + std::to_string(p), {{0, 1.5, 0}, {1.5, 2, std::size_t(p % 4)}, {2, 3, 3}}});
  expectWords(chart,
              {"simulated time (s)", "processor", "computing", "forwarding", "blocked", "idle", "P0", "P3"});
  EXPECT_GE(chart.height(), 320);
}

TEST(Chart, ImageChartNamesRegionsAndItsScale) {
  ImageChart chart;
  chart.title = "Regions";
  chart.caption = "balls2, 64x64";
  chart.image = core::Image::filled(64, 64, core::Color(0.2));
  chart.regions = {{0, 0, 32, 64, "0", 100}, {32, 0, 64, 64, "1", 300}};
  chart.scaleLabel = "rays processed (segments)";
  chart.legendNote = "uniform grid";
  expectWords(chart, {"0", "1", "rays processed (segments)", "uniform grid"});
  EXPECT_NE(chartSvg(chart).find("href=\"data:image/png;base64,"), std::string::npos);
}

TEST(Chart, ExtensionPicksTheFormat) {
  const LineChart chart = scalingPlot();
  const fs::path dir = fs::temp_directory_path() / ("raycube_chart_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  writeChart(chart, dir / "a.svg");
  writeChart(chart, dir / "b.PNG");
  std::ifstream svg(dir / "a.svg"), png(dir / "b.PNG", std::ios::binary);
  std::stringstream svgText, pngBytes;
  svgText << svg.rdbuf();
  pngBytes << png.rdbuf();
  EXPECT_EQ(svgText.str().rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_EQ(pngBytes.str().substr(1, 3), "PNG");
  const core::Image back = core::readPng(dir / "b.PNG");
  EXPECT_EQ(back.width, int(chart.width()));
  EXPECT_EQ(back.height, int(chart.height()));
  EXPECT_THROW(writeChart(chart, dir / "c.jpg"), std::invalid_argument);
  fs::remove_all(dir);
}

TEST(Chart, InlineSvgHoldsNoUrl) {
  const std::string svg = chartSvgInline(scalingPlot());
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u);
  EXPECT_EQ(svg.find("http"), std::string::npos);
}

TEST(Chart, RasterisedChartIsNotBlank) {
  const core::Image image = chartImage(scalingPlot());
  int dark = 0;
  for (const core::Color& c : image.pixels) dark += c.r < 0.1 && c.g < 0.1 && c.b < 0.1 ? 1 : 0;
  EXPECT_GT(dark, 200) << "axes and text are drawn";
}

TEST(Chart, LinearTicksAreRound) {
  Axis axis;
  const std::vector<double> values{0.03, 0.41};
  const AxisRange range = axisRange(axis, values);
  EXPECT_LE(range.lo, 0.03);
  EXPECT_GE(range.hi, 0.41);
  const Ticks ticks = ticksFor(axis, range);
  ASSERT_GE(ticks.at.size(), 3u);
  EXPECT_EQ(ticks.labels.front(), "0");
  EXPECT_EQ(ticks.labels[1], "0.1");
  EXPECT_EQ(ticks.labels[3], "0.3") << "no 0.30000000000000004";
}

TEST(Chart, LogAxesEndOnRoundValuesAndTickThem) {
  Axis axis;
  axis.scale = AxisScale::Log;
  const std::vector<double> values{0.0031, 0.29, 0, -1};  // zero and negatives cannot be shown: ignored
  const AxisRange range = axisRange(axis, values);
  EXPECT_DOUBLE_EQ(range.lo, 0.002);
  EXPECT_DOUBLE_EQ(range.hi, 0.5);
  const Ticks ticks = ticksFor(axis, range);
  EXPECT_EQ(ticks.labels,
            (std::vector<std::string>{"0.002", "0.005", "0.01", "0.02", "0.05", "0.1", "0.2", "0.5"}))
      << "three decades or fewer carry 2 and 5 too";
  Axis wide = axis;
  const std::vector<double> many{1e-6, 3e2};
  const Ticks decades = ticksFor(wide, axisRange(wide, many));
  EXPECT_EQ(decades.labels,
            (std::vector<std::string>{"1e-06", "1e-05", "0.0001", "0.001", "0.01", "0.1", "1", "10", "100"}))
      << "many decades: one tick each (the axis ends at 500)";
}

TEST(Chart, Base64MatchesRfc4648) {
  auto encode = [](const std::string& s) {
    return base64(std::span(reinterpret_cast<const unsigned char*>(s.data()), s.size()));
  };
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
}

TEST(Chart, TextIsEscaped) {
  LineChart chart = scalingPlot();
  chart.title = "a < b & \"c\"";
  const std::string svg = chartSvg(chart);
  EXPECT_NE(svg.find("a &lt; b &amp; &quot;c&quot;"), std::string::npos);
  EXPECT_EQ(svg.find("a < b"), std::string::npos);
}

}  // namespace
}  // namespace raycube::host
