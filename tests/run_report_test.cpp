// The run report (--report): one HTML file that refers to nothing outside itself, holds what it was given
// (sections added later included), and renders in a real browser.
#include "host/report/run_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "core/spd/balls.h"
#include "host/chart/load_chart.h"
#include "host/render/render_machine.h"
#include "host/report/machine_stats.h"
#include "host/report/stats_report.h"

namespace raycube::host {
namespace {

namespace fs = std::filesystem;

struct Rendered {
  core::Scene scene = core::makeBalls(1);
  RenderSettings settings;
  MachineReport machine;
  RenderResult result;
  Rendered() {
    settings.width = settings.height = 32;
    settings.progress = false;
    MachineSettings m;
    m.rows = m.columns = 2;
    result = renderMachine(scene, settings, m, &machine);
  }
};

RunReport reportOf(const Rendered& r) {
  RunReport run;
  run.title = "raycube render: " + r.scene.name;
  run.settings = {{"size", "32x32"}, {"processors", "2x2"}};
  run.summary = summaryText(r.scene, r.result) + machineTable(r.machine);
  run.imagePng = pngBytes(r.result.image);
  const std::string caption = runCaption(r.scene, r.settings, r.result);
  addChartSection(run, loadOverlay(r.result.image, r.machine, caption));
  const LoadBalance balance = loadBalanceOf(r.machine);
  addChartSection(run, loadChart(balance.estimated, balance.actualInMetric, caption));
  run.sections.push_back(processorTableSection(machineJson(r.machine).at("processors")));
  return run;
}

// Every value of every src= and href= attribute, and of every CSS url(...).
std::vector<std::string> references(const std::string& html) {
  std::vector<std::string> found;
  static const std::regex attribute(R"re(\b(?:src|href|xlink:href|action|data)\s*=\s*["']?([^"'\s>]*))re",
                                    std::regex::icase);
  static const std::regex cssUrl(R"re(url\(\s*["']?([^"')]*))re", std::regex::icase);
  for (const std::regex* re : {&attribute, &cssUrl})
    for (auto it = std::sregex_iterator(html.begin(), html.end(), *re); it != std::sregex_iterator(); ++it)
      found.push_back((*it)[1].str());
  return found;
}

TEST(RunReport, ReferencesNothingOutsideItself) {
  const Rendered rendered;
  const std::string html = reportHtml(reportOf(rendered));
  EXPECT_EQ(html.find("http:"), std::string::npos);
  EXPECT_EQ(html.find("https:"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  EXPECT_EQ(html.find("<iframe"), std::string::npos);
  EXPECT_FALSE(std::regex_search(html, std::regex(R"(<script[^>]*\bsrc)", std::regex::icase)));
  const std::vector<std::string> refs = references(html);
  EXPECT_GE(refs.size(), 2u) << "the image and the overlay's picture";
  for (const std::string& ref : refs)
    EXPECT_EQ(ref.rfind("data:image/png;base64,", 0), 0u) << ref.substr(0, 80);
}

TEST(RunReport, HoldsImageSettingsSummaryChartsAndTable) {
  const Rendered rendered;
  const RunReport run = reportOf(rendered);
  const std::string html = reportHtml(run);
  EXPECT_NE(html.find("<img class=\"render\""), std::string::npos);
  EXPECT_NE(html.find("<td>processors</td><td>2x2</td>"), std::string::npos);
  EXPECT_NE(html.find("Mrays/s"), std::string::npos) << "the summary";
  EXPECT_NE(html.find(">Figure 15: estimated against actual load per processor</text>"), std::string::npos);
  EXPECT_NE(html.find(">rays processed (segments)</text>"), std::string::npos) << "the overlay's scale";
  EXPECT_NE(html.find("<table class=\"sortable processors\">"), std::string::npos);
  EXPECT_NE(html.find("<script>"), std::string::npos) << "the inline sorting script";
  // Every processor has a row.
  const std::regex idCell("<td data-key=\"/id\">");
  const auto rows =
      std::distance(std::sregex_iterator(html.begin(), html.end(), idCell), std::sregex_iterator());
  EXPECT_EQ(rows, 4);
}

TEST(RunReport, LaterSectionsGoInWhereTheyAreAdded) {
  RunReport run;
  run.title = "t";
  TimelineChart timeline;
  timeline.title = "Simulated-time timeline";
  timeline.time.label = "simulated time (s)";
  timeline.states = {"computing", "idle"};
  timeline.rows = {{"P0", {{0, 1, 0}, {1, 2, 1}}}};
  addChartSection(run, timeline);
  run.sections.push_back({"Scaling", "<p>speed-up table</p>"});
  const std::string html = reportHtml(run);
  const auto timelineAt = html.find("<h2>Simulated-time timeline</h2>");
  const auto scalingAt = html.find("<h2>Scaling</h2>");
  ASSERT_NE(timelineAt, std::string::npos);
  ASSERT_NE(scalingAt, std::string::npos);
  EXPECT_LT(timelineAt, scalingAt);
  EXPECT_NE(html.find(">computing</text>"), std::string::npos);
  EXPECT_NE(html.find("<p>speed-up table</p>"), std::string::npos);
}

// Debian's chromium, headless; empty when it is not installed.
std::string chromiumPath() {
  for (const char* dir : {"/usr/bin", "/usr/local/bin", "/bin"})
    if (fs::exists(fs::path(dir) / "chromium")) return (fs::path(dir) / "chromium").string();
  return "";
}

TEST(RunReport, RendersInHeadlessChromium) {
  const std::string chromium = chromiumPath();
  if (chromium.empty())
    GTEST_SKIP() << "chromium is not installed (apt-get install chromium): report not opened";
  const fs::path dir = fs::temp_directory_path() / ("raycube_report_browser_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "profile");
  const Rendered rendered;
  writeReport(reportOf(rendered), dir / "run.html");
  constexpr int kWidth = 1000, kHeight = 1400;
  const fs::path shot = dir / "shot.png", log = dir / "chromium.log";
  const std::string command =
      "timeout 120 '" + chromium +
      "' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
      "--disable-component-update --disable-sync --user-data-dir='" +
      (dir / "profile").string() + "' --screenshot='" + shot.string() +
      "' --window-size=" + std::to_string(kWidth) + "," + std::to_string(kHeight) + " 'file://" +
      (dir / "run.html").string() + "' > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  if (!fs::exists(shot)) {
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    fs::remove_all(dir);
    GTEST_SKIP() << "chromium could not run (status " << status << "), report not opened; its output:\n"
                 << text.str().substr(0, 2000);
  }
  const core::Image page = core::readPng(shot);
  fs::remove_all(dir);
  EXPECT_EQ(page.width, kWidth);
  EXPECT_EQ(page.height, kHeight);
  std::set<std::uint32_t> colours;
  for (const core::Color& c : page.pixels)
    colours.insert(std::uint32_t(core::linearToSrgb8(c.r)) << 16 |
                   std::uint32_t(core::linearToSrgb8(c.g)) << 8 | core::linearToSrgb8(c.b));
  EXPECT_GT(colours.size(), 50u) << "a blank or nearly blank page: the report did not render";
}

}  // namespace
}  // namespace raycube::host
