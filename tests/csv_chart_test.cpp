// `raycube plot`: a CSV table becomes a line chart, one series per column after the first, the first
// column's heading naming the x axis; empty fields are missing points; a bad field is named by file:line.
#include "host/chart/csv_chart.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace raycube::host {
namespace {

namespace fs = std::filesystem;

fs::path writeCsv(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / (name + "_" + std::to_string(getpid()) + ".csv");
  std::ofstream(path) << text;
  return path;
}

TEST(CsvChart, EachColumnAfterTheFirstIsASeriesAndEmptyFieldsAreMissingPoints) {
  const fs::path csv =
      writeCsv("cost", "primitives,image-parallel,machine 4x4\n10,0.8,0.9\n92,0.9,\n820,1.1,1.3\n");
  const LineChart chart =
      lineChartFromCsv(csv, {.title = "Cost per ray", .caption = "", .yLabel = "us per ray", .logX = true});
  fs::remove(csv);
  EXPECT_EQ(chart.title, "Cost per ray");
  EXPECT_EQ(chart.x.label, "primitives");
  EXPECT_EQ(chart.x.scale, AxisScale::Log);
  EXPECT_EQ(chart.y.scale, AxisScale::Linear);
  EXPECT_EQ(chart.y.label, "us per ray");
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_EQ(chart.series[0].name, "image-parallel");
  EXPECT_EQ(chart.series[0].x, (std::vector<double>{10, 92, 820}));
  EXPECT_EQ(chart.series[0].y, (std::vector<double>{0.8, 0.9, 1.1}));
  EXPECT_EQ(chart.series[1].name, "machine 4x4");
  EXPECT_EQ(chart.series[1].x, (std::vector<double>{10, 820}));
  EXPECT_EQ(chart.series[1].y, (std::vector<double>{0.9, 1.3}));
}

TEST(CsvChart, ABadFieldIsNamedByItsLine) {
  const fs::path csv = writeCsv("bad", "x,y\n1,2\n3,fast\n");
  try {
    lineChartFromCsv(csv, {});
    ADD_FAILURE() << "read a table with a word where a number belongs";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(":3: 'fast' is not a number"), std::string::npos) << e.what();
  }
  fs::remove(csv);
  const fs::path ragged = writeCsv("ragged", "x,y,z\n1,2\n");
  EXPECT_THROW(lineChartFromCsv(ragged, {}), std::runtime_error);
  fs::remove(ragged);
  EXPECT_THROW(lineChartFromCsv("/nonexistent/table.csv", {}), std::runtime_error);
}

}  // namespace
}  // namespace raycube::host
