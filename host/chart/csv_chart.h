#pragma once
// A line chart from a CSV table, for measurements made outside the program (benchmarks/spd_benchmark.sh's
// cost per ray against primitives): `raycube plot`.
#include <filesystem>
#include <string>

#include "host/chart/chart.h"

namespace raycube::host {

struct CsvChartStyle {
  std::string title;
  std::string caption;
  std::string yLabel;  // the x axis is named by the first column's heading
  bool logX = false, logY = false;
};

// The table's first column is x; every other column is one series, named by its heading. Empty fields are
// points a series lacks (a run that was skipped). Throws std::runtime_error naming file:line when the file
// cannot be read or a field is not a number.
LineChart lineChartFromCsv(const std::filesystem::path& csv, const CsvChartStyle& style);

}  // namespace raycube::host
