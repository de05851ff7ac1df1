#include "host/chart/csv_chart.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace raycube::host {
namespace {

std::vector<std::string> fieldsOf(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream text(line);
  for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

double numberIn(const std::string& field, const std::filesystem::path& csv, int line) {
  std::size_t used = 0;
  try {
    const double value = std::stod(field, &used);
    if (used == field.size()) return value;
  } catch (const std::logic_error&) {
  }
  throw std::runtime_error(fmt::format("{}:{}: '{}' is not a number", csv.string(), line, field));
}

}  // namespace

LineChart lineChartFromCsv(const std::filesystem::path& csv, const CsvChartStyle& style) {
  std::ifstream in(csv);
  std::string line;
  if (!in || !std::getline(in, line)) throw std::runtime_error("cannot read " + csv.string());
  const std::vector<std::string> headings = fieldsOf(line);
  if (headings.size() < 2)
    throw std::runtime_error(csv.string() + ":1: expected a heading for x and one per series");
  LineChart chart;
  chart.title = style.title;
  chart.caption = style.caption;
  chart.x = {.label = headings[0], .scale = style.logX ? AxisScale::Log : AxisScale::Linear};
  chart.y = {.label = style.yLabel, .scale = style.logY ? AxisScale::Log : AxisScale::Linear};
  for (std::size_t s = 1; s < headings.size(); ++s) chart.series.push_back(Series{.name = headings[s]});
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = fieldsOf(line);
    if (fields.size() != headings.size())
      throw std::runtime_error(fmt::format("{}:{}: expected {} fields, got {}", csv.string(), number,
                                           headings.size(), fields.size()));
    const double x = numberIn(fields[0], csv, number);
    for (std::size_t s = 1; s < fields.size(); ++s) {
      if (fields[s].empty()) continue;
      chart.series[s - 1].x.push_back(x);
      chart.series[s - 1].y.push_back(numberIn(fields[s], csv, number));
    }
  }
  return chart;
}

}  // namespace raycube::host
