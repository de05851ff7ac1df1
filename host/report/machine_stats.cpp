#include "host/report/machine_stats.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "host/chart/load_chart.h"

namespace raycube::host {
namespace {

std::uint64_t loadOf(const ProcessorReport& p) {
  return p.node.processed.totalRays();
}

template <class Array>
std::uint64_t sum(const Array& a) {
  return std::accumulate(a.begin(), a.end(), std::uint64_t(0));
}

std::uint64_t costOf(const ProcessorReport& p) {
  const core::TraceCounters& c = p.node.processed;
  return c.intersectionTests + c.boxTests + c.cellSteps;
}

const char* balanceName(Balance balance) {
  return std::array{"auto", "uniform", "bsp"}[std::size_t(balance)];
}

// The partition made, and what chose it when the run asked for either: "auto: uniform, estimated span
// 1.7e+06 against 2.2e+06 for the BSP on 2 cores".
std::string balanceText(const MachineReport& report) {
  const char* made = balanceName(report.settings.balance);
  if (report.balanceAsked != Balance::Auto) return made;
  if (!report.partitionForecast) return fmt::format("auto: {}, the only one fitting", made);
  const PartitionForecast& f = *report.partitionForecast;
  const bool bsp = report.settings.balance == Balance::Bsp;
  return fmt::format("auto: {}, estimated span {:.3g} against {:.3g} for the {} on {} cores", made,
                     bsp ? f.bspSpan : f.uniformSpan, bsp ? f.uniformSpan : f.bspSpan, bsp ? "grid" : "BSP",
                     f.cores);
}

nlohmann::json forecastJson(const MachineReport& report) {
  if (!report.partitionForecast) return nullptr;
  const PartitionForecast& f = *report.partitionForecast;
  return {{"cores", f.cores}, {"bspSpan", f.bspSpan}, {"uniformSpan", f.uniformSpan}};
}

}  // namespace

LoadBalance loadBalanceOf(const MachineReport& report) {
  LoadBalance b;
  std::vector<double> rays, cost;
  for (const ProcessorReport& p : report.processors) {
    rays.push_back(double(loadOf(p)));
    cost.push_back(double(costOf(p)));
  }
  b.actualRays = normalisedToMean(rays);
  b.actualCost = normalisedToMean(cost);
  b.estimated = normalisedToMean(report.estimatedLoad);
  if (!b.actualRays.empty()) {
    b.raysMaxOverMean = *std::max_element(b.actualRays.begin(), b.actualRays.end());
    b.raysMinOverMean = *std::min_element(b.actualRays.begin(), b.actualRays.end());
    b.costMaxOverMean = *std::max_element(b.actualCost.begin(), b.actualCost.end());
    b.costMinOverMean = *std::min_element(b.actualCost.begin(), b.actualCost.end());
  }
  // Figure 15 compares the estimate with the rays each processor actually processed, whatever the metric.
  b.actualInMetric = b.actualRays;
  if (b.estimated.size() == b.actualInMetric.size() && b.estimated.size() > 1)
    b.pearson = pearson(b.estimated, b.actualInMetric);
  return b;
}

namespace {

// The cell structure used (3.3) and what the regions held: their databases and, with light volumes (3.7.2),
// the objects those hold (summed over the lights), mean and max over the processors.
std::string cellsLine(const MachineReport& report) {
  std::size_t held = 0, heldMax = 0, light = 0, lightMax = 0;
  for (const ProcessorReport& p : report.processors) {
    held += p.node.heldObjects;
    heldMax = std::max(heldMax, p.node.heldObjects);
    light += p.node.lightObjects;
    lightMax = std::max(lightMax, p.node.lightObjects);
  }
  const double n = double(std::max<std::size_t>(report.processors.size(), 1));
  const node::CellStructure cells = cellsFor(report.settings);
  std::string text = cells == node::CellStructure::Paper
                         ? fmt::format("  cells: paper (3.3's super-cells, level {}, cut by depth)",
                                       report.settings.cellLevel)
                         : std::string("  cells: bvh (a BVH per region)");
  text += fmt::format("; objects held per processor mean {:.1f} max {}", double(held) / n, heldMax);
  const node::LightRayMode mode = report.settings.lightRays;
  if (mode == node::LightRayMode::Messages) return text + "; light rays as messages\n";
  return text + fmt::format(
                    "; light {}s: objects per light volume, summed over the lights, mean {:.1f} max {}, "
                    "light rays traced where they start in {}\n",
                    mode == node::LightRayMode::Cone ? "cone" : "pyramid", double(light) / n, lightMax,
                    cells == node::CellStructure::Paper ? "the regions' cells" : "a BVH");
}

}  // namespace

std::string machineTable(const MachineReport& report) {
  std::uint64_t byKind[core::kRayKinds] = {}, forwarded = 0, refused = 0, leftScene = 0, held = 0;
  for (const ProcessorReport& p : report.processors) {
    for (int k = 0; k < core::kRayKinds; ++k) byKind[k] += p.node.messagesByKind[k];
    forwarded += p.node.forwarded;
    leftScene += p.node.leftScene;
    refused += p.node.refusedPushes;
    held += p.node.primariesHeld;
  }
  std::string text = fmt::format(
      "  machine {}x{}, FIFO {} rays of {} bytes; messages: eye {}, reflected {}, refracted {}, light {}; "
      "forwarded {}; refused pushes {}; steps holding primaries back for the machine's backlog {}; "
      "rays ended with nothing ahead {}\n",
      report.settings.rows, report.settings.columns, fifoRaysFor(report.settings), report.messageBytes,
      byKind[0], byKind[1], byKind[2], byKind[3], forwarded, refused, held, leftScene);
  text += cellsLine(report);
  const LoadBalance balance = loadBalanceOf(report);
  const bool mapped = !report.hypercubeNode.empty();
  text += fmt::format("  termination: {} token rounds, {} token passes; ", report.tokenRounds,
                      report.tokenPasses);
  text += mapped ? fmt::format("hypercube of dimension {}: {} adjacencies, dilation mean {:.2f} max {}\n",
                               report.hypercubeDimension, report.adjacencyEdges, report.dilationMean,
                               report.dilationMax)
                 : std::string("hypercube not mapped (only the emulated machine, --emulate, needs it)\n");
  const PreprocessingSeconds& pre = report.preprocessing;
  text += fmt::format(
      "  preprocessing: sampling {:.3f} s, partitioning {:.3f} s, pruning {:.3f} s, cells {:.3f} s",
      pre.sampling, pre.partitioning, pre.pruning, pre.cells);
  if (mapped)
    text += fmt::format("; hypercube mapping {:.3f} s{}", pre.mapping,
                        report.settings.emulate ? "" : " (during the synthesis)");
  text += "\n";
  text += fmt::format(
      "  load ({}, {} metric, sub-sampling {}x{}): rays processed max/mean {:.2f} min/mean {:.2f}; cost "
      "max/mean "
      "{:.2f} min/mean {:.2f}; estimate vs actual Pearson r {:.3f}\n",
      balanceText(report), report.settings.loadMetric == LoadMetric::Cost ? "cost" : "rays",
      report.settings.subsampleWindow, report.settings.subsampleWindow, balance.raysMaxOverMean,
      balance.raysMinOverMean, balance.costMaxOverMean, balance.costMinOverMean, balance.pearson);
  text +=
      "  node  pixels objects  cells   segments   tests      sent  received  fwd  refused  est/mean  "
      "act/mean\n";
  for (std::size_t i = 0; i < report.processors.size(); ++i) {
    const node::NodeStats& n = report.processors[i].node;
    text +=
        fmt::format("  {:>4} {:>7} {:>7} {:>6} {:>10} {:>8} {:>9} {:>9} {:>4} {:>8} {:>9.2f} {:>10.2f}\n",
                    n.id, n.area.count(), n.objects, n.cells, n.processed.totalRays(),
                    n.processed.intersectionTests, sum(n.sent), sum(n.received), n.forwarded, n.refusedPushes,
                    i < balance.estimated.size() ? balance.estimated[i] : 0.0, balance.actualInMetric[i]);
  }
  return text;
}

namespace {

// A processor's face FIFOs (left, right, up, down): rays through them and how full they ran.
nlohmann::json facesJson(const ProcessorReport& p) {
  const node::NodeStats& n = p.node;
  nlohmann::json faces = nlohmann::json::array();
  for (int f = 0; f < node::kFaces; ++f) {
    const queues::QueueStats& q = p.outgoing[f];
    faces.push_back({{"sent", n.sent[f]},
                     {"received", n.received[f]},
                     {"fifoHighWater", q.highWater},
                     {"fifoMeanOccupancy", q.meanOccupancy()},
                     {"fifoRefusedPushes", q.refusedPushes}});
  }
  return faces;
}

nlohmann::json processorJson(const ProcessorReport& p) {
  const node::NodeStats& n = p.node;
  nlohmann::json rays, spawned, finished, messages;
  for (int k = 0; k < core::kRayKinds; ++k) {
    const char* name = core::rayKindName(core::RayKind(k));
    rays[name] = n.processed.rays[k];
    spawned[name] = n.spawned[k];
    finished[name] = n.finished[k];
    messages[name] = n.messagesByKind[k];
  }
  return {{"id", n.id},
          {"pixels", n.area.count()},
          {"area", {n.area.x0, n.area.y0, n.area.x1, n.area.y1}},
          {"objects", n.objects},
          {"rearObjects", n.rearObjects},
          {"lightObjects", n.lightObjects},
          {"extraLightObjects", n.extraLightObjects},
          {"lightRaysTracedLocally", n.lightRaysTracedLocally},
          {"cells", n.cells},
          {"bvh", n.bvh},
          {"heldObjects", n.heldObjects},
          {"raysProcessed", rays},
          {"raysSpawned", spawned},
          {"raysFinished", finished},
          {"messagesByKind", messages},
          {"intersectionTests", n.processed.intersectionTests},
          {"cellSteps", n.processed.cellSteps},
          {"boxTests", n.processed.boxTests},
          {"contributions", n.processed.contributions},
          {"faces(left,right,up,down)", facesJson(p)},
          {"forwarded", n.forwarded},
          {"leftScene", n.leftScene},
          {"refusedPushes", n.refusedPushes},
          {"overflowHighWater", n.overflowHighWater},
          {"locks", n.locks},
          {"primariesHeld", n.primariesHeld},
          {"idleSeconds", p.idleSeconds},
          {"blockedSeconds", p.blockedSeconds},
          {"tokenVisits", n.tokenVisits}};
}

nlohmann::json preprocessingJson(const MachineReport& report) {
  return {{"sampling", report.preprocessing.sampling},
          {"partitioning", report.preprocessing.partitioning},
          {"pruning", report.preprocessing.pruning},
          {"cells", report.preprocessing.cells},
          {"mapping", report.preprocessing.mapping},
          {"mappingDuringSynthesis", !report.hypercubeNode.empty() && !report.settings.emulate}};
}

nlohmann::json hypercubeJson(const MachineReport& report) {
  return {{"mapped", !report.hypercubeNode.empty()}, {"dimension", report.hypercubeDimension},
          {"nodeOfProcessor", report.hypercubeNode}, {"adjacencyEdges", report.adjacencyEdges},
          {"dilationMean", report.dilationMean},     {"dilationMax", report.dilationMax}};
}

// --fifo-full lock: the cycle the run stopped on (null when it did not).
nlohmann::json deadlockJson(const MachineReport& report) {
  if (!report.deadlock) return nullptr;
  nlohmann::json deadlock = {{"message", describe(*report.deadlock)}, {"cycle", nlohmann::json::array()}};
  if (report.deadlock->simulatedSeconds >= 0)
    deadlock["simulatedSeconds"] = report.deadlock->simulatedSeconds;
  if (report.deadlock->wallSeconds >= 0) deadlock["wallSeconds"] = report.deadlock->wallSeconds;
  for (const LockedFifo& f : report.deadlock->cycle)
    deadlock["cycle"].push_back({{"from", f.from}, {"to", f.to}, {"face", int(f.face)}, {"rays", f.rays}});
  return deadlock;
}

// Figure 15: estimated against actual load per processor.
nlohmann::json figure15Json(const LoadBalance& balance) {
  return {{"estimatedOverMean", balance.estimated},     {"raysProcessedOverMean", balance.actualRays},
          {"costOverMean", balance.actualCost},         {"actualInMetricOverMean", balance.actualInMetric},
          {"pearsonEstimateVsActual", balance.pearson}, {"raysMaxOverMean", balance.raysMaxOverMean},
          {"raysMinOverMean", balance.raysMinOverMean}, {"costMaxOverMean", balance.costMaxOverMean},
          {"costMinOverMean", balance.costMinOverMean}};
}

}  // namespace

nlohmann::json machineJson(const MachineReport& report) {
  nlohmann::json processors = nlohmann::json::array();
  for (const ProcessorReport& p : report.processors) processors.push_back(processorJson(p));
  return {{"rows", report.settings.rows},
          {"balance", balanceName(report.settings.balance)},
          {"balanceAsked", balanceName(report.balanceAsked)},
          {"partitionForecast", forecastJson(report)},
          {"loadMetric", report.settings.loadMetric == LoadMetric::Cost ? "cost" : "rays"},
          {"subsampleWindow", report.settings.subsampleWindow},
          {"subsampledRays", report.subsampledRays},
          {"preprocessingSeconds", preprocessingJson(report)},
          {"hypercube", hypercubeJson(report)},
          {"figure15", figure15Json(loadBalanceOf(report))},
          {"columns", report.settings.columns},
          {"queueCapacity", fifoRaysFor(report.settings)},
          {"fifoFull", fifoFullFor(report.settings) == node::FifoFull::Lock ? "lock" : "overflow"},
          {"deadlock", deadlockJson(report)},
          {"cells", cellsName(report.settings.cells)},
          {"cellLevel", report.settings.cellLevel},
          {"messageBytes", report.messageBytes},
          {"contributionsAccumulated", report.contributionsAccumulated},
          {"tokenRounds", report.tokenRounds},
          {"tokenPasses", report.tokenPasses},
          {"processors", processors}};
}

std::string partitionName(const MachineReport& report) {
  const MachineSettings& m = report.settings;
  if (m.balance == Balance::Uniform) return fmt::format("uniform {}x{} grid", m.rows, m.columns);
  return fmt::format("BSP of {} areas ({} metric, sub-sampling {}x{})", m.rows * m.columns,
                     m.loadMetric == LoadMetric::Cost ? "cost" : "rays", m.subsampleWindow,
                     m.subsampleWindow);
}

ImageChart loadOverlay(const core::Image& image, const MachineReport& report, std::string caption) {
  ImageChart chart;
  chart.title = "Regions and the rays each processor processed";
  chart.caption = std::move(caption);
  chart.image = image;
  chart.scaleLabel = "rays processed (segments)";
  chart.legendNote = report.settings.balance == Balance::Uniform ? "uniform grid" : "BSP partition";
  auto clampX = [&](int v) { return std::clamp(v, 0, image.width); };
  auto clampY = [&](int v) { return std::clamp(v, 0, image.height); };
  for (const ProcessorReport& p : report.processors) {
    // Sample k sits on pixel k (centres) or on its top-left corner (corners): either way the area
    // [x0, x1) x [y0, y1) of samples covers the same pixels, clamped to the image.
    const node::SampleRect& a = p.node.area;
    chart.regions.push_back({clampX(a.x0), clampY(a.y0), clampX(a.x1), clampY(a.y1),
                             std::to_string(p.node.id), double(loadOf(p))});
  }
  return chart;
}

}  // namespace raycube::host
