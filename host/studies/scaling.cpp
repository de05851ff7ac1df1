#include "host/studies/scaling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>

#include "host/render/render_machine.h"
#include "host/report/emulated_report.h"

namespace raycube::host {
namespace {

// Table 2 of the paper: balls (size 2), 128x128, on the iPSC/1, in seconds.
const std::map<int, double> kTable2Seconds{{1, 13941}, {4, 4621}, {16, 2262}, {32, 1263}};

bool isTable2Case(const core::Scene& scene, const RenderSettings& settings) {
  return scene.name == "balls2" && settings.width == 128 && settings.height == 128 &&
         settings.shading.maxDepth == 5;
}

}  // namespace

std::pair<int, int> nearSquareGrid(int processors) {
  int rows = 1;
  for (int r = 1; r * r <= processors; ++r)
    if (processors % r == 0) rows = r;
  return {rows, processors / rows};
}

std::vector<ScalingPoint> scalingStudy(const core::Scene& scene, const RenderSettings& settings,
                                       MachineSettings machine, std::vector<int> processors) {
  if (!machine.emulate) throw std::invalid_argument("a scaling study runs in simulated time: --emulate");
  std::sort(processors.begin(), processors.end());
  processors.erase(std::unique(processors.begin(), processors.end()), processors.end());
  std::vector<ScalingPoint> points;
  for (int p : processors) {
    std::tie(machine.rows, machine.columns) = nearSquareGrid(p);
    MachineReport report;
    try {
      renderMachine(scene, settings, machine, &report);
    } catch (const MachineDeadlocked& deadlock) {
      std::cerr << "scaling: " << p << " processors: " << deadlock.what() << '\n';
    }
    ScalingPoint point;
    point.processors = p;
    point.rows = machine.rows;
    point.columns = machine.columns;
    point.makespan = report.deadlock ? std::nan("") : report.emulated->makespan;
    point.preprocessing = report.emulated->preprocessing.seconds;
    point.endToEnd = point.preprocessing + point.makespan;
    point.nodeSpeed = report.emulated->nodeSpeed;
    if (report.deadlock) point.deadlockAt = report.deadlock->simulatedSeconds;
    point.blockedShare = blockedShare(report);
    point.rayMessages = report.emulated->rayMessages;
    point.wallSeconds = report.emulated->wallSeconds;
    points.push_back(point);
    const ScalingPoint& base = points.front();
    points.back().speedup = base.makespan / point.makespan * base.processors;
    points.back().efficiency = points.back().speedup / p;
    points.back().endToEndSpeedup = base.makespan / point.endToEnd * base.processors;
    points.back().endToEndEfficiency = points.back().endToEndSpeedup / p;
    if (!report.deadlock)
      std::cerr << fmt::format(
          "scaling: {} processors: {:.1f} simulated s, {:.1f} end to end with the host's {:.1f} ({:.1f} s "
          "wall)\n",
          p, point.makespan, point.endToEnd, point.preprocessing, point.wallSeconds);
  }
  return points;
}

std::string scalingTable(const std::vector<ScalingPoint>& points, const core::Scene& scene,
                         const RenderSettings& settings) {
  const bool paper = isTable2Case(scene, settings);
  std::string text = fmt::format("{} at {}x{}, depth {}: simulated time against processors{}\n", scene.name,
                                 settings.width, settings.height, settings.shading.maxDepth,
                                 paper ? " (table 2's configuration; the paper's times beside)" : "");
  text +=
      "  procs  grid     simulated s   speedup  efficiency   host s  end to end s  e2e eff.  blocked  "
      "ray messages  wall s";
  text += paper ? "   paper s  paper eff.  ours/paper\n" : "\n";
  for (const ScalingPoint& p : points) {
    if (p.deadlockAt >= 0) {
      text += fmt::format(
          "  {:>5}  {:>2}x{:<3} deadlock at {:.1f} simulated s (--fifo-full lock); {:.1f}% blocked\n",
          p.processors, p.rows, p.columns, p.deadlockAt, 100 * p.blockedShare);
      continue;
    }
    text += fmt::format(
        "  {:>5}  {:>2}x{:<3} {:>13.1f} {:>9.2f} {:>11.2f} {:>8.1f} {:>13.1f} {:>9.2f} {:>7.1f}% {:>13} "
        "{:>7.2f}",
        p.processors, p.rows, p.columns, p.makespan, p.speedup, p.efficiency, p.preprocessing, p.endToEnd,
        p.endToEndEfficiency, 100 * p.blockedShare, p.rayMessages, p.wallSeconds);
    if (const auto published = kTable2Seconds.find(p.processors); paper && published != kTable2Seconds.end())
      text += fmt::format(" {:>9.0f} {:>11.2f} {:>11.2f}", published->second,
                          kTable2Seconds.at(1) / published->second / p.processors,
                          p.makespan / published->second);
    text += '\n';
  }
  return text;
}

LineChart scalingPlot(const std::vector<ScalingPoint>& points, const core::Scene& scene,
                      const RenderSettings& settings, const std::string& platform) {
  LineChart chart;
  chart.title = fmt::format("Speed-up against processors, in simulated time on {}", platform);
  chart.caption = fmt::format("{} at {}x{}, depth {}; speed-up against {} processor{}, labels: efficiency",
                              scene.name, settings.width, settings.height, settings.shading.maxDepth,
                              points.empty() ? 1 : points.front().processors,
                              !points.empty() && points.front().processors == 1 ? "" : "s, scaled");
  chart.x = {.label = "processors", .scale = AxisScale::Log};
  chart.y = {.label = "speed-up (simulated time of the smallest count / time)", .scale = AxisScale::Log};
  Series ours{.name = "raycube (simulated)"};
  for (const ScalingPoint& p : points) {
    if (p.deadlockAt >= 0) continue;  // no time to plot
    ours.x.push_back(p.processors);
    ours.y.push_back(p.speedup);
    ours.pointLabels.push_back(fmt::format("{:.2f}", p.efficiency));
  }
  Series ideal{.name = "ideal (efficiency 1)"};
  if (!ours.x.empty())
    ideal = {ideal.name, {ours.x.front(), ours.x.back()}, {ours.x.front(), ours.x.back()}, {}};
  chart.series.push_back(std::move(ours));
  if (platform == "ipsc1" && isTable2Case(scene, settings)) {
    Series paper{.name = "Priol & Bouatouch, table 2 (iPSC/1)"};
    for (const auto& [processors, seconds] : kTable2Seconds) {
      paper.x.push_back(processors);
      paper.y.push_back(kTable2Seconds.at(1) / seconds);
      paper.pointLabels.push_back(fmt::format("{:.2f}", kTable2Seconds.at(1) / seconds / processors));
    }
    chart.series.push_back(std::move(paper));
  }
  chart.series.push_back(std::move(ideal));
  return chart;
}

void writeScalingCsv(const std::vector<ScalingPoint>& points, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the CSV", path.string()));
  out << "processors,rows,columns,simulated_seconds,speedup,efficiency,blocked_share,ray_messages,wall_"
         "seconds,preprocessing_seconds,end_to_end_seconds,end_to_end_efficiency\n";
  for (const ScalingPoint& p : points)
    out << fmt::format("{},{},{},{:.9g},{:.6g},{:.6g},{:.6g},{},{:.3f},{:.9g},{:.9g},{:.6g}\n", p.processors,
                       p.rows, p.columns, p.makespan, p.speedup, p.efficiency, p.blockedShare, p.rayMessages,
                       p.wallSeconds, p.preprocessing, p.endToEnd, p.endToEndEfficiency);
}

}  // namespace raycube::host
