// Static load distribution (Priol & Bouatouch 3.7.1): the sub-sampled estimate, the BSP of the screen, and
// what they achieve on the machine.
#include <gtest/gtest.h>

#include <random>

#include "core/intersect.h"
#include "core/spd/balls.h"
#include "core/whitted.h"
#include "host/prepare/bsp_partition.h"
#include "host/prepare/load_estimate.h"
#include "host/prepare/screen_partition.h"
#include "host/render/sequential_renderers.h"
#include "host/report/machine_stats.h"
#include "machine_test_support.h"
#include "node/region_map.h"

namespace raycube::host {
namespace {

using namespace testing_support;

LoadSample randomSegments(int count, double w, double h, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> x(0, w), y(0, h);
  LoadSample sample;
  for (int i = 0; i < count; ++i)
    sample.segments.push_back(ScreenSegment{x(random), y(random), x(random), y(random), 1.0});
  return sample;
}

// Any processor count, power of two or not, tiles the screen with non-empty areas (RegionMap checks the
// tiling: no overlap, no hole).
TEST(Bsp, TilesTheScreenForAnyProcessorCount) {
  const core::Scene scene = core::makeBalls(1);
  for (int side : {9, 40, 64}) {
    const core::View view(scene.camera, side, side, core::Sampling::Centers);
    const node::ScreenLines lines(view);
    const LoadSample sample = randomSegments(500, side, side, unsigned(side));
    for (int p : {1, 2, 3, 5, 7, 16, 31, 32, 64, 81}) {
      if (p > side * side) continue;
      for (LoadMetric metric : {LoadMetric::Rays, LoadMetric::Cost}) {
        const auto areas = bspPartition(side, side, p, sample, metric);
        ASSERT_EQ(int(areas.size()), p);
        EXPECT_NO_THROW(node::RegionMap(areas, lines)) << side << " px, " << p << " processors";
      }
    }
  }
  EXPECT_THROW(bspPartition(2, 2, 5, LoadSample{}, LoadMetric::Rays), std::invalid_argument);
}

// The first cut's sides are cut on two cores where there are two: the same areas, in the same order, as on
// one, for either metric and any processor count.
TEST(Bsp, TheSameAreasOnOneCoreOrTwo) {
  const LoadSample sample = randomSegments(4000, 300, 200, 5);
  for (int p : {2, 3, 16, 17, 64})
    for (LoadMetric metric : {LoadMetric::Rays, LoadMetric::Cost}) {
      const auto one = bspPartition(300, 200, p, sample, metric, 1);
      const auto two = bspPartition(300, 200, p, sample, metric, 2);
      ASSERT_EQ(one.size(), two.size());
      for (std::size_t k = 0; k < one.size(); ++k) {
        EXPECT_EQ(one[k].x0, two[k].x0) << p << " processors, area " << k;
        EXPECT_EQ(one[k].x1, two[k].x1) << p << " processors, area " << k;
        EXPECT_EQ(one[k].y0, two[k].y0) << p << " processors, area " << k;
        EXPECT_EQ(one[k].y1, two[k].y1) << p << " processors, area " << k;
      }
    }
  EXPECT_THROW(bspPartition(2, 2, 5, LoadSample{}, LoadMetric::Rays, 2), std::invalid_argument);
}

// With the load concentrated on one side, the BSP gives that side small areas.
TEST(Bsp, FollowsTheLoad) {
  LoadSample sample;
  for (int i = 0; i < 1000; ++i)
    sample.segments.push_back(ScreenSegment{10.0 + i % 7, 10.0 + i % 11, 10.5 + i % 7, 10.5 + i % 11, 1});
  sample.segments.push_back(ScreenSegment{90, 90, 91, 91, 1});
  const auto areas = bspPartition(100, 100, 4, sample, LoadMetric::Rays);
  const std::vector<double> loads = estimateAreas(areas, sample, LoadMetric::Rays).loads;
  const double total = loads[0] + loads[1] + loads[2] + loads[3];
  for (double l : loads) EXPECT_LT(l, 0.6 * total);
  long long smallest = 100 * 100;
  for (const node::SampleRect& a : areas) smallest = std::min(smallest, a.count());
  EXPECT_LT(smallest, 100 * 100 / 8);
}

// The loads each side of every line, as the BSP weighs them, are what weighing each line apart piece by
// piece gives (the ray metric exactly, its sums being whole numbers): pieces lying on lines, degenerate,
// short ones a line cuts once, long ones cut by many, reaching past the area, along either axis.
TEST(Bsp, LoadsAcrossLinesAreThoseOfEachLineWeighedApart) {
  auto weighApart = [](const std::vector<ScreenSegment>& pieces, int axis, double k, LoadMetric metric,
                       double& below, double& above) {
    below = above = 0;
    for (const ScreenSegment& s : pieces) {
      const double a = axis == 0 ? s.x0 : s.y0, b = axis == 0 ? s.x1 : s.y1;
      const double lo = std::min(a, b), hi = std::max(a, b), w = s.weight;
      if (metric == LoadMetric::Rays) {
        below += lo < k ? w : 0;
        above += hi >= k ? w : 0;
      } else if (lo >= k) {
        above += w;
      } else if (hi <= k) {
        below += w;
      } else {
        below += costOfPiece(w, (k - lo) / (hi - lo));
        above += costOfPiece(w, 1 - (k - lo) / (hi - lo));
      }
    }
  };
  std::mt19937 random(7);
  const int lo = 3, hi = 61;
  std::uniform_real_distribution<double> along(lo - 2, hi + 2), length(0, 3), weight(1, 40);
  std::uniform_int_distribution<int> line(lo, hi), kind(0, 4);
  std::vector<ScreenSegment> pieces;
  for (int i = 0; i < 4000; ++i) {
    double a = along(random), b = along(random);
    switch (kind(random)) {
      case 0:
        a = b = line(random);
        break;  // a point on a line
      case 1:
        b = a;
        break;  // a point between lines
      case 2:
        b = a + length(random);
        break;  // short: cut by a few lines, or none
      case 3:
        a = line(random), b = line(random);
        break;  // ends on lines
      default:
        break;  // anywhere, long ones too
    }
    pieces.push_back(ScreenSegment{a, b, b, a, 1.0});
  }
  for (LoadMetric metric : {LoadMetric::Rays, LoadMetric::Cost}) {
    if (metric == LoadMetric::Cost)
      for (ScreenSegment& s : pieces) s.weight = weight(random);
    for (int axis : {0, 1}) {
      const LineLoads loads = loadsAcrossLines(pieces, axis, lo, hi, metric);
      ASSERT_EQ(loads.below.size(), std::size_t(hi - lo - 1));
      ASSERT_EQ(loads.above.size(), std::size_t(hi - lo - 1));
      for (int k = lo + 1; k < hi; ++k) {
        double below, above;
        weighApart(pieces, axis, k, metric, below, above);
        const std::size_t i = std::size_t(k - lo - 1);
        if (metric == LoadMetric::Rays) {
          EXPECT_EQ(loads.below[i], below) << "line " << k;
          EXPECT_EQ(loads.above[i], above) << "line " << k;
        } else {
          EXPECT_NEAR(loads.below[i], below, 1e-12 * (below + above)) << "line " << k;
          EXPECT_NEAR(loads.above[i], above, 1e-12 * (below + above)) << "line " << k;
        }
      }
    }
  }
  EXPECT_TRUE(loadsAcrossLines(pieces, 0, 5, 6, LoadMetric::Cost).below.empty());  // no line between
  // Beyond every piece a side weighs exactly nothing (the BSP then cuts by area), whatever was added and
  // taken away before it.
  std::vector<ScreenSegment> left;
  for (const ScreenSegment& s : pieces)
    if (std::max(s.x0, s.x1) < 20) left.push_back(s);
  for (LoadMetric metric : {LoadMetric::Rays, LoadMetric::Cost}) {
    const LineLoads loads = loadsAcrossLines(left, 0, lo, hi, metric);
    for (int k = 20; k < hi; ++k) EXPECT_EQ(loads.above[std::size_t(k - lo - 1)], 0.0) << "line " << k;
  }
}

// Figure 9: a segment crossing a splitting line counts in both regions (ray metric); with the cost metric
// each piece counts one whole (its message and walk set-up) and the work above it in proportion to its
// length.
TEST(LoadEstimate, SplitSegmentsCountOnBothSides) {
  LoadSample sample;
  sample.segments.push_back(ScreenSegment{1, 5, 9, 5, 8.0});
  const std::vector<node::SampleRect> halves{{0, 5, 0, 10}, {5, 10, 0, 10}};
  const auto rays = estimateAreas(halves, sample, LoadMetric::Rays).loads;
  EXPECT_EQ(rays[0], 8.0);
  EXPECT_EQ(rays[1], 8.0);
  const auto cost = estimateAreas(halves, sample, LoadMetric::Cost).loads;
  EXPECT_DOUBLE_EQ(cost[0], 1 + 7.0 / 2);
  EXPECT_DOUBLE_EQ(cost[1], 1 + 7.0 / 2);
  // A quarter of the length: one plus a quarter of the work.
  const std::vector<node::SampleRect> quarters{{0, 3, 0, 10}, {3, 10, 0, 10}};
  const auto uneven = estimateAreas(quarters, sample, LoadMetric::Cost).loads;
  EXPECT_DOUBLE_EQ(uneven[0], 1 + 7.0 / 4);
  EXPECT_DOUBLE_EQ(uneven[1], 1 + 7.0 * 3 / 4);
}

// Every area's load, clipping every segment against it in order: what estimateAreas' loads must equal exactly
// (it only skips the areas far from a segment).
std::vector<double> loadsAgainstEveryArea(const std::vector<node::SampleRect>& areas,
                                          const LoadSample& sample, LoadMetric metric) {
  int width = 0, height = 0;
  for (const node::SampleRect& a : areas) {
    width = std::max(width, a.x1);
    height = std::max(height, a.y1);
  }
  std::vector<double> loads(areas.size(), 0.0);
  for (std::size_t i = 0; i < areas.size(); ++i) {
    const node::SampleRect& a = areas[i];
    for (const ScreenSegment& s : sample.segments) {
      ScreenSegment piece;
      if (!clipSegment(s, a.x0, a.y0, a.x1, a.y1, metric, piece)) continue;
      if (a.x1 < width && std::min(piece.x0, piece.x1) >= a.x1) continue;
      if (a.y1 < height && std::min(piece.y0, piece.y1) >= a.y1) continue;
      loads[i] += piece.weight * sample.raysPerSegment;
    }
  }
  return loads;
}

// Random segments, points, and segments lying on the areas' boundaries and corners (integer coordinates):
// the estimate is bit for bit the one that clips every segment against every area.
TEST(LoadEstimate, NearbyAreasGiveExactlyTheLoadsOfEveryArea) {
  for (int side : {7, 100, 512}) {
    LoadSample sample = randomSegments(3000, side, side, unsigned(side) + 1);
    std::mt19937 random{unsigned(side)};
    std::uniform_int_distribution<int> grid(0, side);
    for (int i = 0; i < 2000; ++i) {
      const double x = grid(random), y = grid(random);
      sample.segments.push_back(ScreenSegment{x, y, x, y, 1.0 + i % 3});             // a point
      sample.segments.push_back(ScreenSegment{x, y, double(grid(random)), y, 2.0});  // along a row
      sample.segments.push_back(ScreenSegment{x, y, x, double(grid(random)), 0.5});  // along a column
    }
    sample.raysPerSegment = 64;
    for (int p : {1, 3, 16, 64}) {
      if (p > side * side) continue;
      for (LoadMetric metric : {LoadMetric::Rays, LoadMetric::Cost}) {
        const auto areas = bspPartition(side, side, p, sample, metric);
        EXPECT_EQ(estimateAreas(areas, sample, metric).loads, loadsAgainstEveryArea(areas, sample, metric))
            << side << " px, " << p << " processors";
      }
    }
  }
}

// Where the scene lies ends a ray's segment (node/scene_bounds.h), but every sub-sampled ray still weighs
// somewhere: an eye ray on its pixel, missing everything or not, and a reflected ray that leaves the scene at
// once on the point it starts from. Looking away from the flake, the eye rays are all there is.
TEST(LoadEstimate, RaysLeavingTheSceneStillWeigh) {
  core::Scene scene = core::makeBalls(2);
  const core::View toward(scene.camera, 32, 32, core::Sampling::Centers, 1);
  scene.camera.at = 2.0 * scene.camera.from - scene.camera.at;
  const core::View away(scene.camera, 32, 32, core::Sampling::Centers, 1);
  const core::Whitted shading(scene, core::ShadingOptions{});
  std::vector<core::Box> bounds;
  for (const core::Object& o : scene.objects) bounds.push_back(core::boundsOf(o, 0x1p-16));
  for (const core::View& view : {toward, away}) {
    const LoadSample without = subsampleLoad(scene, view, shading, 4, LoadMetric::Rays, true);
    const LoadSample with = subsampleLoad(scene, view, shading, 4, LoadMetric::Rays, true, bounds);
    EXPECT_EQ(with.raysTraced, without.raysTraced);
    EXPECT_EQ(with.segments.size(), without.segments.size());
  }
  EXPECT_EQ(subsampleLoad(scene, away, shading, 4, LoadMetric::Rays, true, bounds).segments.size(), 64u);
}

// 2,000 rays crossing the top-left quarter of a 100 x 100 screen's 4 x 4 grid cells, [0, 25) x [0, 25), and
// nothing elsewhere: the grid holds them all in one area, whole; the BSP spreads them over its processors,
// cutting them.
LoadSample raysInOneCorner() {
  LoadSample sample;
  for (int i = 0; i < 2000; ++i)
    sample.segments.push_back(ScreenSegment{1.0 + i % 23, 1.0 + i % 19, 24.0 - i % 17, 24.0 - i % 13, 1});
  return sample;
}

MachineSettings gridOf(int rows, int columns, Balance balance) {
  MachineSettings m;
  m.rows = rows;
  m.columns = columns;
  m.balance = balance;
  m.loadMetric = LoadMetric::Rays;
  return m;
}

TEST(ScreenPartition, TheSpanIsTheBusiestAreaOrTheWholeLoadOverTheCores) {
  EXPECT_DOUBLE_EQ(estimatedSpan({1, 2, 3, 10}, 1), 16);
  EXPECT_DOUBLE_EQ(estimatedSpan({1, 2, 3, 10}, 2), 10);
  EXPECT_DOUBLE_EQ(estimatedSpan({4, 4, 4, 4}, 2), 8);
  EXPECT_DOUBLE_EQ(estimatedSpan({4, 4, 4, 4}, 4), 4);
  EXPECT_DOUBLE_EQ(estimatedSpan({}, 2), 0);
}

// Auto makes the partition whose estimated span is shorter: the BSP where each processor has a core (the
// busiest sets the pace), the grid where one core runs them all (the cut rays' pieces are extra work).
TEST(ScreenPartition, AutoWeighsTheCoresTheProcessorsShare) {
  const core::Scene scene = core::makeBalls(1);
  const core::View view(scene.camera, 100, 100, core::Sampling::Centers);
  const LoadSample sample = raysInOneCorner();
  const MachineSettings automatic = gridOf(4, 4, Balance::Auto);

  const ScreenPartition ownCores = partitionScreen(view, sample, automatic, 16);
  EXPECT_EQ(ownCores.balance, Balance::Bsp);
  ASSERT_TRUE(ownCores.forecast.has_value());
  EXPECT_DOUBLE_EQ(ownCores.forecast->uniformSpan, 2000);  // every ray in one area
  EXPECT_LT(ownCores.forecast->bspSpan, 1000);
  EXPECT_EQ(ownCores.regions.gridColumns(), 0);

  const ScreenPartition oneCore = partitionScreen(view, sample, automatic, 1);
  EXPECT_EQ(oneCore.balance, Balance::Uniform);
  ASSERT_TRUE(oneCore.forecast.has_value());
  EXPECT_EQ(oneCore.forecast->cores, 1);
  EXPECT_DOUBLE_EQ(oneCore.forecast->uniformSpan, 2000);
  EXPECT_GT(oneCore.forecast->bspSpan, 2000);  // the same rays, cut into more pieces
  EXPECT_EQ(oneCore.regions.gridColumns(), 4);
  EXPECT_EQ(oneCore.regions.areaOf(0).x1, 25);
}

// Where no ray crosses a cut (points: light rays traced where they start, scenes without secondary rays),
// both partitions hold the same pieces and, on one core, have the same span but for the rounding of sums
// taken in another order: a tie, which keeps the paper's BSP.
TEST(ScreenPartition, EqualSpansKeepTheBsp) {
  const core::Scene scene = core::makeBalls(1);
  const core::View view(scene.camera, 100, 100, core::Sampling::Centers);
  LoadSample sample;
  for (int i = 0; i < 5000; ++i) {
    const double x = 0.5 + (i * 37) % 100, y = 0.5 + (i * 61) % 100;
    sample.segments.push_back(ScreenSegment{x, y, x, y, 0.1 * (1 + i % 7)});
  }
  for (int cores : {1, 2}) {
    const ScreenPartition made = partitionScreen(view, sample, gridOf(4, 4, Balance::Auto), cores);
    ASSERT_TRUE(made.forecast.has_value());
    EXPECT_NEAR(made.forecast->uniformSpan, made.forecast->bspSpan, 1e-9 * made.forecast->bspSpan);
    EXPECT_EQ(made.balance, Balance::Bsp) << cores << " cores";
  }
}

// A partition asked for by name is made whatever the forecast; Auto takes the only one that fits.
TEST(ScreenPartition, AskedByNameOrTheOnlyOneFitting) {
  const core::Scene scene = core::makeBalls(1);
  const core::View view(scene.camera, 100, 100, core::Sampling::Centers);
  const LoadSample sample = raysInOneCorner();
  const ScreenPartition bsp = partitionScreen(view, sample, gridOf(4, 4, Balance::Bsp), 1);
  EXPECT_EQ(bsp.balance, Balance::Bsp);
  EXPECT_FALSE(bsp.forecast.has_value());
  const ScreenPartition uniform = partitionScreen(view, sample, gridOf(4, 4, Balance::Uniform), 16);
  EXPECT_EQ(uniform.balance, Balance::Uniform);
  EXPECT_FALSE(uniform.forecast.has_value());
  // 1 x 128 columns: no grid of 100 sample columns holds them; the BSP does.
  const ScreenPartition onlyBsp = partitionScreen(view, sample, gridOf(1, 128, Balance::Auto), 1);
  EXPECT_EQ(onlyBsp.balance, Balance::Bsp);
  EXPECT_FALSE(onlyBsp.forecast.has_value());
  EXPECT_EQ(onlyBsp.regions.processors(), 128);
}

// The machine's report names the partition made and what chose it; the image is the reference's either way.
TEST(ScreenPartition, TheReportSaysWhichPartitionAutoMade) {
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = settingsFor(32);
  MachineSettings m;
  m.rows = 4;
  m.columns = 4;
  ASSERT_EQ(m.balance, Balance::Auto);  // the default
  MachineReport report;
  const RenderResult result = renderMachine(scene, settings, m, &report);
  EXPECT_TRUE(core::bitIdentical(result.image, renderReference(scene, settings).image));
  EXPECT_EQ(report.balanceAsked, Balance::Auto);
  ASSERT_TRUE(report.partitionForecast.has_value());
  const PartitionForecast& f = *report.partitionForecast;
  EXPECT_EQ(report.settings.balance, f.uniformSpan < f.bspSpan ? Balance::Uniform : Balance::Bsp);
  EXPECT_GE(f.cores, 1);
  EXPECT_LE(f.cores, 16);
  const std::string table = machineTable(report);
  EXPECT_NE(table.find("auto: "), std::string::npos) << table;
  const nlohmann::json json = machineJson(report);
  EXPECT_EQ(json["balanceAsked"], "auto");
  EXPECT_EQ(json["partitionForecast"]["cores"], f.cores);
}

MachineSettings bspMachine(int processors, LoadMetric metric, int window, node::LightRayMode lights,
                           std::size_t capacity = 8) {
  MachineSettings m;
  m.rows = 1;
  m.columns = processors;
  m.balance = Balance::Bsp;
  m.loadMetric = metric;
  m.subsampleWindow = window;
  m.lightRays = lights;
  m.queueCapacity = capacity;
  return m;
}

// Every balance, metric, light-ray mode, processor count and capacity renders the reference image.
TEST(LoadDistribution, EveryCombinationMatchesTheReference) {
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = settingsFor(sanitized() ? 16 : 40);
  const RenderResult reference = renderReference(scene, settings);
  const std::vector<int> counts = sanitized() ? std::vector<int>{5, 16} : std::vector<int>{4, 5, 16, 32, 64};
  for (int p : counts)
    for (LoadMetric metric : {LoadMetric::Rays, LoadMetric::Cost})
      for (node::LightRayMode lights :
           {node::LightRayMode::Messages, node::LightRayMode::Cone, node::LightRayMode::Pyramid})
        for (std::size_t capacity : {std::size_t(1), std::size_t(128)}) {
          const std::string label = "bsp " + std::to_string(p) + " metric " + std::to_string(int(metric)) +
                                    " lights " + std::to_string(int(lights)) + " capacity " +
                                    std::to_string(capacity);
          MachineReport report;
          const RenderResult result = renderMachineWatched(
              scene, settings, bspMachine(p, metric, 4, lights, capacity), report, label);
          EXPECT_TRUE(core::bitIdentical(result.image, reference.image)) << label;
          EXPECT_EQ(report.contributionsAccumulated, reference.counters.contributions) << label;
          EXPECT_EQ(int(report.processors.size()), p) << label;
        }
}

// Figure 15 on a uniform grid, where loads differ: the sub-sampled estimate follows the rays processed.
TEST(LoadDistribution, EstimateFollowsTheRaysProcessed) {
  if (sanitized()) GTEST_SKIP() << "a measurement at 128x128";
  const core::Scene scene = core::makeBalls(2);
  MachineSettings m;
  m.rows = 4;
  m.columns = 4;
  m.balance = Balance::Uniform;
  m.loadMetric = LoadMetric::Rays;
  m.subsampleWindow = 2;
  MachineReport report;
  renderMachine(scene, settingsFor(128), m, &report);
  const LoadBalance b = loadBalanceOf(report);
  EXPECT_GT(b.pearson, 0.9);
  for (std::size_t i = 0; i < b.estimated.size(); ++i) EXPECT_NEAR(b.estimated[i], b.actualRays[i], 0.1) << i;
}

// The BSP evens out the rays processed that the uniform grid leaves uneven (balls2, 128x128, 16 processors).
TEST(LoadDistribution, BspBalancesBetterThanTheUniformGrid) {
  if (sanitized()) GTEST_SKIP() << "a measurement at 128x128";
  const core::Scene scene = core::makeBalls(2);
  MachineReport uniform, bsp;
  MachineSettings u;
  u.balance = Balance::Uniform;
  renderMachine(scene, settingsFor(128), u, &uniform);
  renderMachine(scene, settingsFor(128), bspMachine(16, LoadMetric::Rays, 2, node::LightRayMode::Pyramid),
                &bsp);
  const LoadBalance bu = loadBalanceOf(uniform), bb = loadBalanceOf(bsp);
  EXPECT_LT(bb.raysMaxOverMean, bu.raysMaxOverMean);
  EXPECT_LE(bb.raysMaxOverMean, 1.15);
  EXPECT_GE(bb.raysMinOverMean, 0.85);
}

// The paper's table 1 case (balls2, 128x128) on 16 and 32 processors, sub-sampling window 2: the refined
// metric evens out the work (intersection tests and cell steps) better than the paper's rays metric, while
// every processor's rays processed stay within 30% of the mean.
TEST(LoadDistribution, CostMetricBalancesWorkBetterThanTheRaysMetric) {
  if (sanitized()) GTEST_SKIP() << "a measurement at 128x128";
  const core::Scene scene = core::makeBalls(2);
  for (int p : {16, 32}) {
    MachineReport byCost, byRays;
    renderMachine(scene, settingsFor(128), bspMachine(p, LoadMetric::Cost, 2, node::LightRayMode::Pyramid),
                  &byCost);
    renderMachine(scene, settingsFor(128), bspMachine(p, LoadMetric::Rays, 2, node::LightRayMode::Pyramid),
                  &byRays);
    const LoadBalance cost = loadBalanceOf(byCost), rays = loadBalanceOf(byRays);
    EXPECT_LT(cost.costMaxOverMean, rays.costMaxOverMean) << p << " processors";
    EXPECT_LE(cost.raysMaxOverMean, 1.3) << p << " processors";
    EXPECT_GE(cost.raysMinOverMean, 0.7) << p << " processors";
  }
}

}  // namespace
}  // namespace raycube::host
