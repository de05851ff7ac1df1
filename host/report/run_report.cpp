#include "host/report/run_report.h"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace raycube::host {
namespace {

constexpr const char* kStyle = R"css(
body { font-family: "DejaVu Sans", sans-serif; margin: 24px; color: #222; background: #fff; }
h1 { font-size: 22px; } h2 { font-size: 17px; margin-top: 28px; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; font-size: 12px; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: right; }
th { background: #eef; cursor: pointer; user-select: none; }
table.settings td:first-child { text-align: left; font-weight: bold; }
pre { background: #f6f6f6; padding: 10px; font-size: 12px; overflow-x: auto; }
img.render { image-rendering: pixelated; width: 512px; max-width: 100%; height: auto; border: 1px solid #ccc; }
svg { max-width: 100%; height: auto; }
)css";

// Click a heading to sort the table by that column (numbers numerically), again to reverse.
constexpr const char* kSortScript = R"js(
document.querySelectorAll('table.sortable th').forEach((th, column) => th.addEventListener('click', () => {
  const body = th.closest('table').tBodies[0], rows = Array.from(body.rows);
  const ascending = th.dataset.order !== 'ascending';
  const key = r => { const t = r.cells[column].textContent, v = parseFloat(t); return isNaN(v) ? t : v; };
  rows.sort((a, b) => (key(a) < key(b) ? -1 : key(a) > key(b) ? 1 : 0) * (ascending ? 1 : -1));
  th.dataset.order = ascending ? 'ascending' : 'descending';
  rows.forEach(r => body.appendChild(r));
}));
)js";

std::string settingsTable(const std::vector<std::pair<std::string, std::string>>& settings) {
  std::string html = "<table class=\"settings\">\n";
  for (const auto& [name, value] : settings)
    html += fmt::format("<tr><td>{}</td><td>{}</td></tr>\n", markupEscaped(name), markupEscaped(value));
  return html + "</table>\n";
}

}  // namespace

void addChartSection(RunReport& report, const Chart& chart) {
  report.sections.push_back({chart.title, chartSvgInline(chart)});
}

ReportSection processorTableSection(const nlohmann::json& processors) {
  std::string html = "<table class=\"sortable processors\">\n<thead><tr>";
  for (const ProcessorColumn& c : kProcessorColumns)
    html += fmt::format("<th>{}</th>", markupEscaped(c.heading));
  html += "</tr></thead>\n<tbody>\n";
  for (const nlohmann::json& p : processors) {
    html += "<tr>";
    for (const ProcessorColumn& c : kProcessorColumns) {
      const nlohmann::json::json_pointer pointer(c.pointer);
      // The JSON's own number formatting, so each cell reads back as exactly the --stats value.
      html += fmt::format("<td data-key=\"{}\">{}</td>", c.pointer,
                          p.contains(pointer) ? markupEscaped(p.at(pointer).dump()) : "");
    }
    html += "</tr>\n";
  }
  html += "</tbody>\n</table>\n";
  return {"Per processor (click a heading to sort)", html};
}

std::string reportHtml(const RunReport& report) {
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{0}</title>\n"
      "<style>{1}</style>\n</head>\n<body>\n<h1>{0}</h1>\n",
      markupEscaped(report.title), kStyle);
  html += "<h2>Settings</h2>\n" + settingsTable(report.settings);
  if (!report.imagePng.empty())
    html += fmt::format("<h2>Image</h2>\n<img class=\"render\" alt=\"the rendered image\" src=\"{}\">\n",
                        pngDataUri(report.imagePng));
  html += "<h2>Summary</h2>\n<pre>" + markupEscaped(report.summary) + "</pre>\n";
  for (const ReportSection& s : report.sections)
    html += fmt::format("<section>\n<h2>{}</h2>\n{}</section>\n", markupEscaped(s.title), s.html);
  html += fmt::format("<script>{}</script>\n</body>\n</html>\n", kSortScript);
  return html;
}

void writeReport(const RunReport& report, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write report " + path.string());
  out << reportHtml(report);
  if (!out) throw std::runtime_error("failed writing report " + path.string());
}

}  // namespace raycube::host
