// `raycube tradeoff`: each knob's sweep is measured against a converged reference.
#include "host/studies/tradeoff.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "core/spd/balls.h"

namespace raycube::host {
namespace {

TEST(Tradeoff, MoreAccurateSettingsComeCloserToTheReference) {
  const core::Scene scene = core::makeBalls(1);
  RenderSettings base;
  base.width = base.height = 24;
  base.progress = false;
  TradeoffOptions options;
  options.runs = 1;
  options.referenceRaysPerSample = 16;
  int heard = 0;
  const auto rows = measureTradeoff(scene, base, options, [&](const TradeoffRow&) { ++heard; });
  ASSERT_EQ(heard, int(rows.size()));
  std::map<std::string, std::vector<TradeoffRow>> byKnob;
  for (const TradeoffRow& r : rows) {
    EXPECT_GT(r.seconds, 0) << r.knob << " " << r.setting;
    EXPECT_TRUE(std::isfinite(r.rmse));
    byKnob[r.knob].push_back(r);
  }
  for (const char* knob : {"depth", "min-weight", "spp"}) EXPECT_GE(byKnob[knob].size(), 4u) << knob;
  // Precision: float, then double; the double row is the SPD default and so the depth-5 row's picture.
  ASSERT_EQ(byKnob["precision"].size(), 2u);
  EXPECT_EQ(byKnob["precision"][0].setting, "float");
  EXPECT_EQ(byKnob["precision"][1].rmse, byKnob["depth"][4].rmse);
  EXPECT_NE(byKnob["precision"][0].rmse, byKnob["precision"][1].rmse) << "float renders another picture";
  // Deeper trees and more rays per pixel never move away from the converged image.
  for (const char* knob : {"depth", "spp"})
    for (std::size_t i = 1; i < byKnob[knob].size(); ++i)
      EXPECT_LE(byKnob[knob][i].rmse, byKnob[knob][i - 1].rmse + 1e-12)
          << knob << " " << byKnob[knob][i].setting;
  EXPECT_GT(byKnob["depth"].front().rmse, byKnob["depth"].back().rmse);
  EXPECT_GT(byKnob["spp"].back().counters.of(core::RayKind::Eye),
            byKnob["spp"].front().counters.of(core::RayKind::Eye));

  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "raycube_tradeoff_test.csv";
  writeTradeoffCsv(rows, csv);
  std::ifstream in(csv);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, int(rows.size()) + 1);
  // The CSV redraws the plot: what it holds reads back.
  const std::vector<TradeoffRow> back = readTradeoffCsv(csv);
  ASSERT_EQ(back.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].knob, rows[i].knob);
    EXPECT_EQ(back[i].setting, rows[i].setting);
    EXPECT_NEAR(back[i].seconds, rows[i].seconds, 1e-6);
    EXPECT_EQ(back[i].counters.rays, rows[i].counters.rays);
    EXPECT_NEAR(back[i].rmse, rows[i].rmse, 1e-5 * rows[i].rmse);
  }
  std::filesystem::remove(csv);
  const LineChart plot = tradeoffPlot(rows, "balls1, 24x24");
  ASSERT_EQ(plot.series.size(), std::size(kKnobs));
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    EXPECT_EQ(plot.series[k].name, kKnobs[k]);
    EXPECT_EQ(plot.series[k].x.size(), byKnob[kKnobs[k]].size());
    EXPECT_EQ(plot.series[k].pointLabels.front(), byKnob[kKnobs[k]].front().setting);
  }
  EXPECT_EQ(plot.y.scale, AxisScale::Log);
  const std::string svg = chartSvg(plot);
  for (const char* knob : kKnobs) EXPECT_NE(svg.find(std::string(">") + knob + "</text>"), std::string::npos);
  EXPECT_NE(svg.find("RMSE"), std::string::npos);
  EXPECT_NE(tradeoffTable(rows).find("min-weight"), std::string::npos);
}

TEST(Tradeoff, SubsamplingWindowsReportTheirCostAndBalance) {
  const core::Scene scene = core::makeBalls(2);
  RenderSettings base;
  base.width = base.height = 32;
  base.progress = false;
  const auto rows = measureSubsampling(scene, base, 4, 1);
  ASSERT_EQ(rows.size(), 5u);
  for (const SubsampleRow& r : rows) {
    EXPECT_GT(r.preprocessSeconds, 0) << r.window;
    EXPECT_GE(r.raysMaxOverMean, 1.0) << r.window;
    EXPECT_LE(r.raysMinOverMean, 1.0) << r.window;
  }
  EXPECT_EQ(rows.front().window, 16);
  EXPECT_EQ(rows.back().window, 1);
  EXPECT_NE(subsampleTable(rows).find("16x16"), std::string::npos);
}

TEST(Tradeoff, MalformedCsvNamesItsLine) {
  const std::filesystem::path csv = std::filesystem::temp_directory_path() / "raycube_tradeoff_bad.csv";
  {
    std::ofstream out(csv);
    out << "knob,setting,seconds,eye_rays,reflected_rays,refracted_rays,light_rays,rmse,psnr_db,max_error\n";
    out << "depth,1,0.02,65536,0,0,180220,0.12,18.38,0.482\n";
    out << "depth,2,fast,65536,0,0,180220,0.12,18.38,0.482\n";
  }
  try {
    readTradeoffCsv(csv);
    ADD_FAILURE() << "no error for a malformed line";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("raycube_tradeoff_bad.csv:3"), std::string::npos) << e.what();
  }
  std::filesystem::remove(csv);
}

}  // namespace
}  // namespace raycube::host
