// The machine in simulated time on SimGrid (host/engines/simgrid/emulated_machine.h): the same image as every
// mode, the same simulated time on every run, and times that can be worked out by hand.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "host/prepare/load_estimate.h"
#include "host/render/sequential_renderers.h"
#include "host/report/emulated_report.h"
#include "host/studies/scaling.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using testing_support::renderAndCompare;
using testing_support::renderMachineWatched;
using testing_support::settingsFor;

// The machine in emulated time with an overflow list behind full FIFOs, so that the small capacities here
// test saturation, not the paper's deadlocks (ipsc1 locks by default: fifo_full_test has those).
MachineSettings emulated(int rows, int columns, const std::string& platform = "ipsc1") {
  MachineSettings m;
  m.rows = rows;
  m.columns = columns;
  m.emulate = builtinPlatform(platform);
  m.fifoFull = node::FifoFull::Overflow;
  return m;
}

TEST(EmulatedMachine, ImageIsTheReferenceAtAnyPartitionCapacityAndLightMode) {
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = settingsFor(32);
  const RenderResult reference = renderReference(scene, settings);
  for (const auto& [rows, columns, capacity, lights, balance] :
       std::vector<std::tuple<int, int, std::size_t, node::LightRayMode, Balance>>{
           {1, 1, 128, node::LightRayMode::Messages, Balance::Uniform},
           {2, 2, 1, node::LightRayMode::Messages, Balance::Bsp},
           {3, 5, 1, node::LightRayMode::Pyramid, Balance::Uniform},
           {4, 4, 128, node::LightRayMode::Messages, Balance::Bsp},
           {2, 3, 2, node::LightRayMode::Cone, Balance::Bsp}}) {
    MachineSettings m = emulated(rows, columns);
    m.queueCapacity = capacity;
    m.lightRays = lights;
    m.balance = balance;
    renderAndCompare(scene, reference, settings, m,
                     fmt::format("ipsc1 {}x{} capacity {} lights {}", rows, columns, capacity, int(lights)));
  }
}

TEST(EmulatedMachine, TheSameRunGivesTheSameSimulatedTimeToTheLastDigit) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings m = emulated(4, 4);
  m.lightRays = node::LightRayMode::Messages;
  m.queueCapacity = 2;  // saturation: the most timing-sensitive case
  std::vector<MachineReport> reports(2);
  for (MachineReport& r : reports) renderMachineWatched(scene, settingsFor(48), m, r, "determinism");
  ASSERT_TRUE(reports[0].emulated && reports[1].emulated);
  EXPECT_EQ(reports[0].emulated->makespan, reports[1].emulated->makespan);
  EXPECT_EQ(reports[0].emulated->rayMessages, reports[1].emulated->rayMessages);
  for (std::size_t p = 0; p < reports[0].processors.size(); ++p) {
    EXPECT_EQ(reports[0].processors[p].computeSeconds, reports[1].processors[p].computeSeconds) << p;
    EXPECT_EQ(reports[0].processors[p].blockedSeconds, reports[1].processors[p].blockedSeconds) << p;
    EXPECT_EQ(reports[0].processors[p].node.processed.intersectionTests,
              reports[1].processors[p].node.processed.intersectionTests)
        << p;
  }
}

// Issue 40: under the paper's cells, the emulated default, light rays traced where they start walk cells of
// their light's volume (3.3, 3.7.2), so a light cone, holding more objects than a light pyramid, costs more
// tests and more computing time; the image stays the reference's, and the time the same run to run.
TEST(EmulatedMachine, UnderThePaperCellsALightConeCostsMoreThanALightPyramid) {
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = settingsFor(32);
  const RenderResult reference = renderReference(scene, settings);
  for (const auto& [rows, columns] : std::vector<std::pair<int, int>>{{4, 4}, {8, 8}}) {
    std::map<node::LightRayMode, MachineReport> reports;
    for (node::LightRayMode mode : {node::LightRayMode::Cone, node::LightRayMode::Pyramid}) {
      MachineSettings m = emulated(rows, columns);
      m.lightRays = mode;
      const std::string label = fmt::format("{}x{} {}", rows, columns, int(mode));
      MachineReport& report = reports[mode];
      const RenderResult result = renderMachineWatched(scene, settings, m, report, label);
      testing_support::expectMachineMatchesReference(reference, result, report, label);
      EXPECT_EQ(report.settings.cells, node::CellStructure::Paper) << label << ": the emulated default";
      MachineReport again;
      renderMachineWatched(scene, settings, m, again, label + " again");
      ASSERT_TRUE(report.emulated && again.emulated);
      EXPECT_EQ(report.emulated->makespan, again.emulated->makespan) << label;
    }
    const MachineReport &cone = reports[node::LightRayMode::Cone],
                        &pyramid = reports[node::LightRayMode::Pyramid];
    std::uint64_t coneTests = 0, pyramidTests = 0, fewer = 0;
    double coneSeconds = 0, pyramidSeconds = 0;
    for (std::size_t p = 0; p < cone.processors.size(); ++p) {
      const node::NodeStats &c = cone.processors[p].node, &y = pyramid.processors[p].node;
      EXPECT_GE(c.lightObjects, y.lightObjects) << "processor " << p;
      fewer += y.lightObjects < c.lightObjects;
      EXPECT_GT(c.lightRaysTracedLocally, 0u) << "processor " << p;
      EXPECT_EQ(c.lightRaysTracedLocally, y.lightRaysTracedLocally) << "processor " << p;
      coneTests += c.processed.intersectionTests;
      pyramidTests += y.processed.intersectionTests;
      coneSeconds += cone.processors[p].computeSeconds;
      pyramidSeconds += pyramid.processors[p].computeSeconds;
    }
    EXPECT_GT(fewer, 0u) << rows << "x" << columns << ": some pyramid holds fewer objects than its cone";
    EXPECT_GT(coneTests, pyramidTests) << rows << "x" << columns;
    EXPECT_GT(coneSeconds, pyramidSeconds) << rows << "x" << columns;
  }
}

// A platform written for a test: one node at one flop-equivalent per second and a host link that costs
// nothing.
std::filesystem::path oneFreeNodePlatform() {
  const auto path = std::filesystem::temp_directory_path() / "raycube_one_free_node.xml";
  std::ofstream(path) << R"(<?xml version='1.0'?>
<!DOCTYPE platform SYSTEM "https://simgrid.org/simgrid.dtd">
<platform version="4.1">
  <zone id="machine" routing="Full">
    <host id="node-0" speed="1f"/>
    <host id="manager" speed="1f"/>
    <link id="node-0:manager" bandwidth="1e30Bps" latency="0s"/>
    <route src="node-0" dst="manager" symmetrical="YES"><link_ctn id="node-0:manager"/></route>
  </zone>
</platform>
)";
  return path;
}

// One processor whose only cost is one second per ray segment, and a host link that costs nothing: the
// simulated time is the number of segments it processed, to the last bit.
TEST(EmulatedMachine, OneProcessorTakesExactlyItsChargedWork) {
  const core::Scene scene = core::makeBalls(1);
  MachineSettings m = emulated(1, 1);
  m.emulate = userPlatform(oneFreeNodePlatform(), {});
  m.emulate->costs = CostTable{0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0};
  MachineReport report;
  renderMachineWatched(scene, settingsFor(16), m, report, "hand");
  const double segments = double(report.processors[0].node.processed.totalRays());
  EXPECT_EQ(report.processors[0].computeSeconds, segments);
  EXPECT_NEAR(report.emulated->makespan, segments, 1e-9 * segments);
  EXPECT_EQ(report.processors[0].blockedSeconds, 0);
  EXPECT_EQ(report.emulated->nodeSpeed, 1);
}

// A cost table's nodeSpeed of twice the platform's halves the compute time of the same work; links, and
// messages (charged in seconds), do not change.
TEST(EmulatedMachine, ComputeTimeScalesWithTheNodeSpeed) {
  const core::Scene scene = core::makeBalls(1);
  MachineSettings slow = emulated(1, 2), fast = emulated(1, 2);
  for (MachineSettings* m : {&slow, &fast})
    m->emulate->costs.sendSeconds = m->emulate->costs.receiveSeconds = 0;
  MachineReport a, b;
  renderMachineWatched(scene, settingsFor(16), slow, a, "slow");
  fast.emulate->nodeSpeed = 2 * a.emulated->nodeSpeed;
  renderMachineWatched(scene, settingsFor(16), fast, b, "fast");
  EXPECT_EQ(b.emulated->nodeSpeed, 2 * a.emulated->nodeSpeed);
  for (std::size_t p = 0; p < a.processors.size(); ++p)
    EXPECT_DOUBLE_EQ(a.processors[p].computeSeconds, 2 * b.processors[p].computeSeconds) << p;
}

// Messages cost seconds of the CPU that pays them, at any node speed: a ray or the token sent costs the
// sender sendSeconds, received the receiver receiveSeconds (a token visit is one of each).
TEST(EmulatedMachine, MessagesCostTheirSecondsOnTheCpuThatPays) {
  const core::Scene scene = core::makeBalls(1);
  for (const double speedFactor : {1.0, 3.0}) {
    MachineSettings m = emulated(1, 2);
    m.lightRays = node::LightRayMode::Messages;
    m.emulate->costs = CostTable{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.25, 0.5, 0};
    MachineReport report;
    renderMachineWatched(scene, settingsFor(16), m, report, "messages");
    if (speedFactor != 1.0) {
      m.emulate->nodeSpeed = speedFactor * report.emulated->nodeSpeed;
      renderMachineWatched(scene, settingsFor(16), m, report, "messages, faster nodes");
    }
    std::uint64_t messages = 0;
    for (const ProcessorReport& p : report.processors) {
      std::uint64_t sent = p.node.tokenVisits, received = p.node.tokenVisits;
      for (auto n : p.node.sent) sent += n;
      for (auto n : p.node.received) received += n;
      messages += sent;
      EXPECT_NEAR(p.computeSeconds, 0.25 * double(sent) + 0.5 * double(received), 1e-9 * p.computeSeconds)
          << "processor " << p.node.id << ", node speed x" << speedFactor;
    }
    EXPECT_GT(messages, 2u) << "the two processors exchanged rays";
  }
}

// Store and forward on the iPSC/1: on a BSP whose regions map onto non-adjacent hypercube nodes, messages
// are relayed, which costs the relays CPU; every relayed message crossed one more link.
TEST(EmulatedMachine, StoreAndForwardRelaysCostTheRelaysCpu) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings m =
      emulated(1, 24);  // 24 regions on a 5-cube: the mapping leaves some neighbours 2+ hops apart
  m.lightRays = node::LightRayMode::Messages;
  MachineReport report;
  renderMachineWatched(scene, settingsFor(48), m, report, "relays");
  ASSERT_GT(report.dilationMax, 1) << "this partition no longer needs relays; pick another";
  double forwarding = 0;
  std::uint64_t sent = 0;
  for (const ProcessorReport& p : report.processors) {
    forwarding += p.forwardSeconds;
    for (auto s : p.node.sent) sent += s;
  }
  EXPECT_GT(forwarding, 0);
  EXPECT_GT(report.emulated->rayMessages, sent) << "relayed messages cross more links than were sent";
}

TEST(EmulatedMachine, CostFilesAreCheckedWithFileAndLine) {
  const auto path = std::filesystem::temp_directory_path() / "raycube_costs_test.txt";
  std::ofstream(path) << "# iPSC/1, slower spheres\nsphereTest 40\nrouting direct\nnodeSpeed -1\n";
  EmulatedPlatform p = builtinPlatform("ipsc1");
  try {
    applyCostFile(path, p);
    FAIL() << "a negative speed was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ":4"), std::string::npos) << e.what();
  }
  EXPECT_EQ(p.costs.sphereTest, 40);
  EXPECT_EQ(p.routing, Routing::Direct);
  EXPECT_THROW(builtinPlatform("cm5"), std::invalid_argument);
  // The flop-equivalent message costs of former cost tables name what replaced them.
  std::ofstream(path) << "messageSent 30\n";
  try {
    applyCostFile(path, p);
    FAIL() << "a former message cost was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(
        std::string(e.what()).find(path.string() + ":1: 'messageSent' (flop-equivalents) is now sendSeconds"),
        std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

// The shipped cost tables (host/machine/platforms/*.costs) spell out CostTable's hand counts of computation,
// so a user's platform without --costs computes as the built-in ones do; they differ in routing and in
// their messages' seconds (the iPSC/1's derived software overheads, the cluster's former flop-equivalents).
TEST(EmulatedMachine, ShippedPlatformsCarryTheHandCountedCosts) {
  const EmulatedPlatform ipsc1 = builtinPlatform("ipsc1"), cluster = builtinPlatform("cluster");
  CostTable ipsc1Costs, clusterCosts;
  ipsc1Costs.sendSeconds = ipsc1Costs.receiveSeconds = 0.5e-3;
  ipsc1Costs.relaySeconds = 1.0e-3;
  clusterCosts.sendSeconds = clusterCosts.receiveSeconds = 75e-9;
  clusterCosts.relaySeconds = 150e-9;
  EXPECT_EQ(ipsc1.costs, ipsc1Costs);
  EXPECT_EQ(cluster.costs, clusterCosts);
  EXPECT_EQ(ipsc1.routing, Routing::StoreAndForward);
  EXPECT_EQ(cluster.routing, Routing::Direct);
  EXPECT_EQ(ipsc1.platformFile.filename(), "ipsc1.xml");
  EXPECT_FALSE(ipsc1.nodeSpeed) << "the speed is the platform's";
}

// The scaling plot names itself, its axes and its curves in the SVG's text; the paper's curve only where
// the paper's numbers apply (its configuration, on the iPSC/1).
TEST(Scaling, PlotCarriesItsWordsAndThePapersCurveOnlyForTable2) {
  auto hasText = [](const std::string& svg, const std::string& words) {
    return svg.find(">" + markupEscaped(words) + "</text>") != std::string::npos;
  };
  const core::Scene scene = core::makeBalls(2);
  RenderSettings settings = settingsFor(128);
  settings.shading.maxDepth = 5;
  std::vector<ScalingPoint> points(3);
  for (auto [p, processors, seconds] : {std::tuple{0, 1, 12000.0}, {1, 4, 4000.0}, {2, 16, 1500.0}}) {
    points[p].processors = processors;
    points[p].makespan = seconds;
    points[p].speedup = 12000 / seconds;
    points[p].efficiency = points[p].speedup / processors;
  }
  const LineChart plot = scalingPlot(points, scene, settings, "ipsc1");
  const std::string svg = chartSvg(plot);
  for (const std::string& words : {plot.title, plot.caption, plot.x.label, plot.y.label,
                                   std::string("raycube (simulated)"), std::string("ideal (efficiency 1)"),
                                   std::string("Priol & Bouatouch, table 2 (iPSC/1)"), std::string("0.50")})
    EXPECT_TRUE(hasText(svg, words)) << words;
  EXPECT_NE(plot.title.find("ipsc1"), std::string::npos);
  EXPECT_NE(plot.x.label.find("processors"), std::string::npos);
  ASSERT_EQ(plot.series.size(), 3u);
  EXPECT_DOUBLE_EQ(plot.series[1].y[1], 13941.0 / 4621) << "table 2's speed-up at 4 processors";
  EXPECT_EQ(scalingPlot(points, scene, settings, "cluster").series.size(), 2u) << "the paper ran no cluster";
  EXPECT_EQ(scalingPlot(points, scene, settingsFor(64), "ipsc1").series.size(), 2u)
      << "not table 2's configuration";
}

TEST(Scaling, NearSquareGrids) {
  EXPECT_EQ(nearSquareGrid(1), std::make_pair(1, 1));
  EXPECT_EQ(nearSquareGrid(32), std::make_pair(4, 8));
  EXPECT_EQ(nearSquareGrid(64), std::make_pair(8, 8));
  EXPECT_EQ(nearSquareGrid(7), std::make_pair(1, 7));
}

// ---- The host pays for its work (issue 40): its preparation in simulated time, before the synthesis.

// A platform written for a test: a manager and two nodes at 100 flop-equivalents per second, each node's link
// to the manager 1000 bytes per second with a quarter-second latency, both ways.
std::filesystem::path twoNodeHostPlatform() {
  const auto path = std::filesystem::temp_directory_path() / "raycube_two_node_host.xml";
  std::ofstream out(path);
  out << "<?xml version='1.0'?>\n<!DOCTYPE platform SYSTEM \"https://simgrid.org/simgrid.dtd\">\n"
         "<platform version=\"4.1\">\n  <zone id=\"m\" routing=\"Full\">\n"
         "    <host id=\"node-0\" speed=\"100f\"/>\n    <host id=\"node-1\" speed=\"100f\"/>\n"
         "    <host id=\"manager\" speed=\"100f\"/>\n";
  for (int n = 0; n < 2; ++n)
    out << fmt::format("    <link id=\"node-{0}:manager\" bandwidth=\"1000Bps\" latency=\"0.25s\"/>\n", n);
  out << "    <link id=\"node-0:node-1\" bandwidth=\"1000Bps\" latency=\"0.25s\"/>\n"
         "    <link id=\"node-1:node-0\" bandwidth=\"1000Bps\" latency=\"0.25s\"/>\n";
  for (int n = 0; n < 2; ++n)
    out << fmt::format(
        "    <route src=\"node-{0}\" dst=\"manager\" symmetrical=\"YES\"><link_ctn id=\"node-{0}:manager\"/>"
        "</route>\n",
        n);
  out << "    <route src=\"node-0\" dst=\"node-1\" symmetrical=\"NO\"><link_ctn "
         "id=\"node-0:node-1\"/></route>\n"
         "    <route src=\"node-1\" dst=\"node-0\" symmetrical=\"NO\"><link_ctn "
         "id=\"node-1:node-0\"/></route>\n"
         "  </zone>\n</platform>\n";
  return path;
}

// Two spheres and a light, 4x4 pixels sub-sampled in windows of 2 (four pixels), a BSP over two processors:
// the host's time worked out by hand from the cost table's prices, the counts the host's code made, and the
// links' figures, against what the host actor was charged.
TEST(HostPreprocessing, EqualsAHandCountOnATinyScene) {
  const core::Scene scene = core::parseNff(
      "v\nfrom 0 -6 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0.01\nresolution 4 4\nl 2 -4 4\n"
      "f 1 0.2 0.2 0.6 0.4 10 0 0\ns -0.8 0 0 0.6\ns 0.8 0 0 0.6\n",
      "two_spheres.nff");
  MachineSettings m;
  m.rows = 1;
  m.columns = 2;
  m.balance = Balance::Bsp;
  m.subsampleWindow = 2;
  m.lightRays = node::LightRayMode::Messages;
  m.emulate = userPlatform(twoNodeHostPlatform(), {});
  CostTable& c = m.emulate->costs;
  c.sendSeconds = 0.5;
  c.receiveSeconds = 0.125;
  MachineReport report;
  renderMachineWatched(scene, settingsFor(4), m, report, "hand count");
  ASSERT_TRUE(report.emulated);
  const HostWork& w = report.hostWork;
  const core::TraceCounters& sampled = w.sampling.processed;
  // What the host's code counted, where a hand can count it too: one eye ray per window, each object
  // against each region.
  EXPECT_EQ(sampled.of(core::RayKind::Eye), 4u);
  EXPECT_EQ(w.regionTests, 2u * 2u);
  EXPECT_GT(w.piecesWeighed, 0u);
  EXPECT_GT(w.mappingSteps, 0u);
  const double speed = 100;
  const double rays = double(sampled.totalRays());
  const double samplingFlops = c.sphereTest * double(sampled.testsByShape[0]) +
                               c.cellStep * double(sampled.boxTests + sampled.cellSteps) +
                               (c.raySegment + c.rayFinished + c.raySpawned) * rays +
                               c.contribution * double(sampled.contributions);
  const double sampling = samplingFlops / speed;
  const double partitioning = c.segmentClip * double(w.piecesWeighed) / speed;
  const double pruning = c.regionTest * double(w.regionTests) / speed;
  const double mapping = c.mappingStep * double(w.mappingSteps) / speed;
  // Each setup in turn: the manager's send overhead, the link's latency and bytes; the last node then pays
  // its receipt.
  const HostPreprocessing& pre = report.emulated->preprocessing;
  EXPECT_EQ(pre.messages, 2u);
  const double transfer = 2 * (c.sendSeconds + 0.25) + double(pre.bytes) / 1000 + c.receiveSeconds;
  const double tolerance = 1e-9;
  EXPECT_NEAR(pre.sampling, sampling, tolerance);
  EXPECT_NEAR(pre.partitioning, partitioning, tolerance);
  EXPECT_NEAR(pre.pruning, pruning, tolerance);
  EXPECT_NEAR(pre.mapping, mapping, tolerance);
  EXPECT_NEAR(pre.transfer, transfer, tolerance);
  EXPECT_NEAR(pre.seconds, sampling + partitioning + pruning + mapping + transfer, tolerance);
  EXPECT_NEAR(report.emulated->endToEnd(), pre.seconds + report.emulated->makespan, tolerance);
  // A node's setup holds at least its objects' boxes and the shared context: far more than a header.
  EXPECT_GT(pre.bytes, 2 * 2 * sizeof(node::EyeBox));
}

// The same run pays the same, to the last digit; what the host pays never moves the synthesis (table 2's
// span), and the grid, which needs no estimate, pays no sub-sampling.
TEST(HostPreprocessing, IsDeterministicAndLeavesTheSynthesisAlone) {
  const core::Scene scene = core::makeBalls(1);
  MachineSettings m = emulated(2, 2);
  m.balance = Balance::Bsp;
  std::vector<MachineReport> reports(3);
  for (int i = 0; i < 2; ++i) renderMachineWatched(scene, settingsFor(16), m, reports[i], "host twice");
  MachineSettings dearer = m;
  dearer.emulate->costs.regionTest *= 10;
  dearer.emulate->costs.mappingStep *= 10;
  renderMachineWatched(scene, settingsFor(16), dearer, reports[2], "dearer host");
  const HostPreprocessing& a = reports[0].emulated->preprocessing;
  EXPECT_GT(a.seconds, 0);
  EXPECT_EQ(a.seconds, reports[1].emulated->preprocessing.seconds);
  EXPECT_EQ(a.bytes, reports[1].emulated->preprocessing.bytes);
  EXPECT_EQ(reports[0].emulated->makespan, reports[1].emulated->makespan);
  EXPECT_EQ(reports[2].emulated->makespan, reports[0].emulated->makespan);
  EXPECT_GT(reports[2].emulated->preprocessing.seconds, a.seconds);
  EXPECT_EQ(reports[2].emulated->preprocessing.sampling, a.sampling);

  MachineSettings grid = m;
  grid.balance = Balance::Uniform;
  MachineReport uniform;
  renderMachineWatched(scene, settingsFor(16), grid, uniform, "grid");
  EXPECT_EQ(uniform.emulated->preprocessing.sampling, 0);
  EXPECT_EQ(uniform.emulated->preprocessing.partitioning, 0);
  EXPECT_GT(uniform.emulated->preprocessing.pruning, 0);
}

// `raycube scaling` shows both: the synthesis (table 2's) and the end-to-end time with the host's
// preparation, with the efficiency of each against the smallest count's synthesis.
TEST(HostPreprocessing, TheScalingStudyShowsTheSynthesisAndTheEndToEndTime) {
  const core::Scene scene = core::makeBalls(1);
  MachineSettings m = emulated(1, 1);
  const std::vector<ScalingPoint> points = scalingStudy(scene, settingsFor(16), m, {1, 4});
  ASSERT_EQ(points.size(), 2u);
  for (const ScalingPoint& p : points) {
    EXPECT_GT(p.preprocessing, 0) << p.processors;
    EXPECT_EQ(p.endToEnd, p.preprocessing + p.makespan) << p.processors;
    EXPECT_DOUBLE_EQ(p.endToEndEfficiency,
                     points[0].makespan * points[0].processors / p.endToEnd / p.processors);
    EXPECT_LT(p.endToEndEfficiency, p.efficiency) << p.processors;
  }
  const std::string table = scalingTable(points, scene, settingsFor(16));
  for (const char* column : {"simulated s", "efficiency", "host s", "end to end s", "e2e eff."})
    EXPECT_NE(table.find(column), std::string::npos) << column;
}

// --subsample auto: the window of the least predicted end-to-end time grows with the processors and, slowly,
// with the resolution (w = cbrt(2 h / c sqrt(P S))).
TEST(HostPreprocessing, TheAutomaticWindowFollowsTheResolution) {
  EXPECT_EQ(subsampleWindowFor(128, 128, 32), 13);
  EXPECT_EQ(subsampleWindowFor(512, 512, 32), 21);
  EXPECT_LT(subsampleWindowFor(128, 128, 4), subsampleWindowFor(128, 128, 32));
  EXPECT_EQ(subsampleWindowFor(4, 4, 64), 4);  // never past the screen
  EXPECT_GE(subsampleWindowFor(1, 1, 1), 1);
}
}  // namespace
}  // namespace raycube::host
