#pragma once
// A run report (--report): one self-contained HTML file a reader opens in a browser, offline. Pictures are
// inline (PNG as base64 data: URIs, charts as inline SVG), style and the table-sorting script are inline,
// and nothing refers to anything outside the file.
//
// To add a section (the simulated-time timeline, the scaling plot, ...): build a Chart and call
// addChartSection(report, chart), or push any self-contained HTML fragment onto report.sections.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "host/chart/chart.h"

namespace raycube::host {

struct ReportSection {
  std::string title;
  std::string html;  // self-contained: inline <svg>, a <table>, text; no URL, no external resource
};

struct RunReport {
  std::string title;
  std::vector<std::pair<std::string, std::string>> settings;  // name, value
  std::string summary;                                        // preformatted text (the summary on stdout)
  std::vector<unsigned char> imagePng;                        // the rendered image; empty for none
  std::vector<ReportSection> sections;                        // in order, after the image and the summary
};

// A section titled with the chart's title, holding its inline SVG.
void addChartSection(RunReport& report, const Chart& chart);
// The per-processor table, sortable by any column, from the "processors" array of machineJson: each cell
// prints the JSON value it shows, so the table says exactly what --stats says.
ReportSection processorTableSection(const nlohmann::json& processors);
std::string reportHtml(const RunReport& report);
// Throws std::runtime_error naming the path when it cannot be written.
void writeReport(const RunReport& report, const std::filesystem::path& path);

// The columns of the per-processor table: heading and JSON pointer into one processor's object.
struct ProcessorColumn {
  const char* heading;
  const char* pointer;
};
inline constexpr ProcessorColumn kProcessorColumns[] = {
    {"processor", "/id"},
    {"pixels", "/pixels"},
    {"objects", "/objects"},
    {"cells", "/cells"},
    {"eye rays", "/raysProcessed/eye"},
    {"reflected rays", "/raysProcessed/reflected"},
    {"refracted rays", "/raysProcessed/refracted"},
    {"light rays", "/raysProcessed/light"},
    {"intersection tests", "/intersectionTests"},
    {"cell steps", "/cellSteps"},
    {"forwarded", "/forwarded"},
    {"refused pushes", "/refusedPushes"},
    {"idle (s)", "/idleSeconds"},
    {"blocked (s)", "/blockedSeconds"},
    {"token visits", "/tokenVisits"},
};

}  // namespace raycube::host
