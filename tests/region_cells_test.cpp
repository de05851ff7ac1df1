// The geometry of a processor's region (Priol & Bouatouch 3.1, 3.3): screen lines, eye-frame rays, cells.
#include "node/region_cells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "core/brute_force.h"
#include "core/spd/balls.h"
#include "node/region_map.h"

namespace raycube::node {
namespace {

struct Fixture {
  core::Scene scene = core::makeBalls(2);
  core::View view{scene.camera, 64, 48, core::Sampling::Centers};
  ScreenLines lines{view};
  std::vector<EyeBox> boxes;
  std::vector<std::uint32_t> all;
  Fixture() {
    for (std::uint32_t i = 0; i < scene.objects.size(); ++i) {
      boxes.push_back(eyeBoxOf(scene.objects[i], view, 2 * scene.largestCoordinate()));
      all.push_back(i);
    }
  }
};

// A ray from near the middle of balls 2 (within half a unit across, from 0.3 behind to 0.7 before its
// centre) in a random direction.
core::Ray rayNearTheMiddle(std::mt19937& random) {
  std::uniform_real_distribution<double> u(-1, 1);
  core::Ray ray;
  ray.origin = core::Vec3(u(random) * 0.5, u(random) * 0.5, u(random) * 0.5 + 0.2);
  ray.direction = glm::normalize(core::Vec3(u(random), u(random), u(random)));
  return ray;
}

TEST(ScreenLines, OuterBoundariesAreAtInfinityAndInnerOnesIncrease) {
  Fixture f;
  EXPECT_EQ(f.lines.at(0, 0), -core::kInfinity);
  EXPECT_EQ(f.lines.at(0, 64), core::kInfinity);
  EXPECT_EQ(f.lines.at(1, 48), core::kInfinity);
  for (int k = 1; k < 63; ++k) EXPECT_LT(f.lines.at(0, k), f.lines.at(0, k + 1));
  for (int k = 1; k < 47; ++k) EXPECT_LT(f.lines.at(1, k), f.lines.at(1, k + 1));
}

// The sample holding a screen coordinate, searched from a guess, is the one a binary search of the table
// finds: on the boundaries themselves, a rounding either side of them, far outside, infinite and NaN, in
// every sub-range, and for the one- and two-sample screens whose spacing says nothing.
TEST(ScreenLines, SampleIndexIsTheTablesBinarySearch) {
  auto reference = [](const ScreenLines& lines, int axis, double value, int lo, int hi) {
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      (lines.at(axis, mid) <= value ? lo : hi) = mid;
    }
    return lo;
  };
  core::Scene scene = core::makeBalls(1);
  std::mt19937 random(7);
  const std::pair<int, int> screens[] = {{64, 48}, {1, 1}, {2, 3}, {513, 7}};
  for (const auto& [width, height] : screens) {
    const core::View view{scene.camera, width, height, core::Sampling::Centers};
    const ScreenLines lines{view};
    for (int axis = 0; axis < 2; ++axis) {
      const int samples = lines.samples(axis);
      std::vector<double> values{core::kInfinity, -core::kInfinity, std::nan(""), 1e300, -1e300, 0.0};
      for (int k = 1; k < samples; ++k)
        for (double v : {lines.at(axis, k), std::nextafter(lines.at(axis, k), -core::kInfinity),
                         std::nextafter(lines.at(axis, k), core::kInfinity)})
          values.push_back(v);
      if (samples >= 3) {  // between the finite boundaries and a little beyond them
        std::uniform_real_distribution<double> anywhere(2 * lines.at(axis, 1) - lines.at(axis, samples - 1),
                                                        2 * lines.at(axis, samples - 1) - lines.at(axis, 1));
        for (int i = 0; i < 200; ++i) values.push_back(anywhere(random));
      }
      for (double value : values)
        for (int lo = 0; lo < samples; lo += std::max(1, samples / 5))
          for (int hi = lo + 1; hi <= samples; hi += std::max(1, samples / 4))
            ASSERT_EQ(lines.sampleIndex(axis, value, lo, hi), reference(lines, axis, value, lo, hi))
                << width << "x" << height << " axis " << axis << " value " << value << " in [" << lo << ", "
                << hi << ")";
    }
  }
}

TEST(EyeFrameRay, EyeRaysStayOnTheirSampleAndNeverCrossAFace) {
  Fixture f;
  const core::Ray ray = f.view.eyeRay(10, 20);
  const EyeFrameRay er = EyeFrameRay::of(ray, f.view);
  EXPECT_EQ(er.screenDirection(0), 0);
  EXPECT_EQ(er.screenDirection(1), 0);
  // Every face through the eye is met at the apex only: not a crossing in front of the eye.
  for (int k = 1; k < 64; ++k) EXPECT_EQ(er.planeCrossing(0, f.lines.at(0, k)), core::kInfinity);
  EXPECT_GT(er.screenAt(0, 1.0), f.lines.at(0, 10));
  EXPECT_LT(er.screenAt(0, 1.0), f.lines.at(0, 11));
}

TEST(EyeFrameRay, SplitsTheLineAtTheEyePlane) {
  Fixture f;
  core::Ray ray;
  ray.origin = f.scene.camera.from - 2.0 * glm::normalize(f.scene.camera.at - f.scene.camera.from);  // behind
  ray.direction = glm::normalize(f.scene.camera.at - f.scene.camera.from + core::Vec3(0.1, 0, 0));
  const EyeFrameRay er = EyeFrameRay::of(ray, f.view);
  EXPECT_FALSE(er.inFront(0));
  const double tz = er.eyePlaneCrossing();
  EXPECT_GT(tz, 0);
  EXPECT_EQ(er.partEnd(0), tz);
  EXPECT_TRUE(er.inFront(tz));
  EXPECT_EQ(er.partEnd(tz), core::kInfinity);
  // The rear part is the last only for an interval that ends at or before the eye plane; the front part is.
  EXPECT_FALSE(er.lastPart(0, core::kInfinity));
  EXPECT_FALSE(er.lastPart(0, 2 * tz));
  EXPECT_TRUE(er.lastPart(0, tz));
  EXPECT_TRUE(er.lastPart(0, tz / 2));
  EXPECT_TRUE(er.lastPart(tz, core::kInfinity));
}

// A walk hands out contiguous, non-overlapping intervals in t order, starting where it was asked to.
TEST(RegionCells, WalkCoversTheIntervalContiguously) {
  Fixture f;
  const SampleRect area{16, 48, 12, 36};
  const RegionCells cells(area, f.lines, 2, true, f.all, f.boxes);
  EXPECT_GT(cells.cellCount(), 16u);
  std::mt19937 random(7);
  int exited = 0, finished = 0;
  for (int n = 0; n < 2000; ++n) {
    const EyeFrameRay er = EyeFrameRay::of(rayNearTheMiddle(random), f.view);
    if (!er.inFront(0)) continue;
    int i, j;
    cells.locate(er, 0, i, j);
    double expected = 0;
    bool contiguous = true;
    RegionExit exit;
    std::uint64_t steps = 0;
    const WalkResult r = cells.walk(
        er, 0, er.partEnd(0), i, j,
        [&](double ta, double tb, const std::vector<std::uint32_t>&) {
          contiguous &= ta >= expected && tb > ta;
          expected = tb;
          return true;
        },
        exit, steps);
    EXPECT_TRUE(contiguous);
    EXPECT_NE(r, WalkResult::Stopped);
    if (r == WalkResult::Exited) {
      ++exited;
      EXPECT_TRUE(exit.sStep != 0 || exit.qStep != 0);
      EXPECT_GE(exit.t, expected);
    } else {
      ++finished;
    }
  }
  EXPECT_GT(exited, 100);
  EXPECT_GT(finished, 10);
}

// A region's objects come as a list with an eye box per entry: cells cut from the list in another order,
// with its boxes in that order, hold the same objects in every cell the walk visits.
TEST(RegionCells, CellsFollowTheirListsBoxesWhateverItsOrder) {
  Fixture f;
  const SampleRect area{36, 60, 26, 46};
  std::vector<std::uint32_t> reversed(f.all.rbegin(), f.all.rend());
  std::vector<EyeBox> reversedBoxes(f.boxes.rbegin(), f.boxes.rend());
  const RegionCells cells(area, f.lines, 2, true, f.all, f.boxes);
  const RegionCells reversedCells(area, f.lines, 2, true, reversed, reversedBoxes);
  EXPECT_EQ(reversedCells.cellCount(), cells.cellCount());
  EXPECT_EQ(reversedCells.objectCount(), cells.objectCount());
  EXPECT_GT(cells.objectCount(), 10u);
  EXPECT_LT(cells.objectCount(), f.all.size());
  std::mt19937 random(5);
  int compared = 0;
  for (int n = 0; n < 500; ++n) {
    const EyeFrameRay er = EyeFrameRay::of(rayNearTheMiddle(random), f.view);
    if (!er.inFront(0)) continue;
    auto cellsAlong = [&](const RegionCells& c) {
      std::vector<std::vector<std::uint32_t>> out;
      int i, j;
      c.locate(er, 0, i, j);
      RegionExit exit;
      std::uint64_t steps = 0;
      c.walk(
          er, 0, er.partEnd(0), i, j,
          [&](double, double, const std::vector<std::uint32_t>& objects) {
            out.push_back(objects);
            std::sort(out.back().begin(), out.back().end());
            return true;
          },
          exit, steps);
      return out;
    };
    const auto along = cellsAlong(cells);
    EXPECT_EQ(cellsAlong(reversedCells), along);
    compared += int(along.size());
  }
  EXPECT_GT(compared, 100);
}

// A region of one cell (a BVH region's) takes walk()'s shortcut: the same intervals, the same end, the same
// exit, the same steps as the general walk through columns, bit for bit, for rays starting anywhere in it
// or outside it (a walk locates them into the region), stopped or not, with and without objects.
TEST(RegionCells, AOneCellRegionWalksAsTheGeneralWalkDoes) {
  Fixture f;
  const std::vector<std::uint32_t> none;
  const std::vector<EyeBox> noBoxes;
  struct Visit {
    double ta, tb;
    std::size_t objects;
    bool operator==(const Visit&) const = default;
  };
  int exited = 0, finished = 0, stopped = 0;
  for (const SampleRect& area :
       {SampleRect{16, 48, 12, 36}, SampleRect{0, 64, 0, 48}, SampleRect{0, 5, 40, 48}})
    for (bool withObjects : {true, false}) {
      const RegionCells cells(area, f.lines, 0, false, withObjects ? f.all : none,
                              withObjects ? f.boxes : noBoxes);
      ASSERT_EQ(cells.cellCount(), 1u);
      std::mt19937 random(13);
      for (int n = 0; n < 3000; ++n) {
        const EyeFrameRay er = EyeFrameRay::of(rayNearTheMiddle(random), f.view);
        const double t0 = n % 3 == 0 ? 0.0 : 0.1 * (n % 7);
        if (!er.inFront(t0)) continue;
        const double tEnd = n % 5 == 0 ? t0 + 0.5 : er.partEnd(t0);
        const bool stopAtTheFirst = n % 2 == 0;
        auto walked = [&](bool general, RegionExit& exit, std::uint64_t& steps, WalkResult& result) {
          std::vector<Visit> visits;
          auto visit = [&](double ta, double tb, const std::vector<std::uint32_t>& objects) {
            visits.push_back(Visit{ta, tb, objects.size()});
            return !stopAtTheFirst;
          };
          result = general ? cells.walkColumns(er, t0, tEnd, 0, 0, visit, exit, steps)
                           : cells.walk(er, t0, tEnd, 0, 0, visit, exit, steps);
          return visits;
        };
        RegionExit shortExit, generalExit;
        std::uint64_t shortSteps = 0, generalSteps = 0;
        WalkResult shortResult, generalResult;
        const std::vector<Visit> shortVisits = walked(false, shortExit, shortSteps, shortResult);
        const std::vector<Visit> generalVisits = walked(true, generalExit, generalSteps, generalResult);
        ASSERT_EQ(shortResult, generalResult) << "ray " << n;
        ASSERT_EQ(shortVisits, generalVisits) << "ray " << n;
        ASSERT_EQ(shortSteps, generalSteps) << "ray " << n;
        if (shortResult == WalkResult::Exited) {
          ASSERT_EQ(shortExit.t, generalExit.t) << "ray " << n;
          ASSERT_EQ(shortExit.sStep, generalExit.sStep) << "ray " << n;
          ASSERT_EQ(shortExit.qStep, generalExit.qStep) << "ray " << n;
        }
        exited += shortResult == WalkResult::Exited;
        finished += shortResult == WalkResult::Finished;
        stopped += shortResult == WalkResult::Stopped;
      }
    }
  EXPECT_GT(exited, 1000);
  EXPECT_GT(finished, 100);
  EXPECT_GT(stopped, 1000);
}

TEST(RegionCells, RefuseObjectsWithoutAnEyeBoxEach) {
  Fixture f;
  std::vector<EyeBox> fewer(f.boxes.begin(), f.boxes.end() - 1);
  EXPECT_THROW(RegionCells(SampleRect{0, 64, 0, 48}, f.lines, 1, true, f.all, fewer), std::invalid_argument);
}

// Conservative assignment: every object a ray hits in front of the eye is listed by the cell owning the hit.
TEST(RegionCells, TheCellOwningAHitHoldsItsObject) {
  Fixture f;
  const SampleRect whole{0, 64, 0, 48};
  const RegionCells cells(whole, f.lines, 3, true, f.all, f.boxes);
  const core::Whitted shading(f.scene, {});
  const core::BruteForce reference(f.scene, shading);
  core::TraceCounters counters;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int n = 0; n < 3000; ++n) {
    core::Ray ray;
    ray.origin = core::Vec3(u(random) * 2, u(random) * 2, u(random) + 0.5);
    ray.direction = glm::normalize(core::Vec3(u(random), u(random), u(random)));
    const core::Hit truth = reference.closestHit(ray, counters);
    const EyeFrameRay er = EyeFrameRay::of(ray, f.view);
    if (!er.inFront(0) || !truth.found() || truth.t >= er.partEnd(0)) continue;
    int i, j;
    cells.locate(er, 0, i, j);
    core::Hit found;
    RegionExit exit;
    std::uint64_t steps = 0;
    cells.walk(
        er, 0, er.partEnd(0), i, j,
        [&](double ta, double tb, const std::vector<std::uint32_t>& objects) {
          for (std::uint32_t o : objects) {
            const core::Hit h{core::nearestHit(f.scene.objects[o], ray, core::kInfinity), o};
            if (h.t >= ta && h.t < tb && h.closerThan(found)) found = h;
          }
          return !found.found();
        },
        exit, steps);
    ++hits;
    EXPECT_EQ(found.object, truth.object);
    EXPECT_EQ(found.t, truth.t);
  }
  EXPECT_GT(hits, 500);
}

TEST(RegionMap, OwnersAndRoutesOnTheGrid) {
  Fixture f;
  const RegionMap map = RegionMap::grid({0, 20, 40, 64}, {0, 16, 48}, f.lines);
  EXPECT_EQ(map.processors(), 6);
  EXPECT_EQ(map.ownerOfSample(0, 0), 0);
  EXPECT_EQ(map.ownerOfSample(63, 47), 5);
  EXPECT_EQ(map.ownerOfSample(20, 16), 4);
  EXPECT_EQ(map.nextHop(0, 5), 1);  // along the row first
  EXPECT_EQ(map.nextHop(2, 5), 5);
  EXPECT_EQ(map.neighbours(0), (std::vector<int>{1, 3}));
  EXPECT_EQ(map.faceToward(4, 1), Face::Up);
  EXPECT_EQ(map.faceToward(4, 3), Face::Left);
  EXPECT_EQ(map.adjacencyEdges(), 7u);
  const core::Ray eye = f.view.eyeRay(30, 30);
  EXPECT_EQ(map.ownerAt(EyeFrameRay::of(eye, f.view), 1.0), map.ownerOfSample(30, 30));
}

// A region's screen rectangle is the lines of its area, infinite on the screen's edges; a ray's points in
// front of the eye lie in the region that holds them exactly where they lie inside its rectangle.
TEST(RegionMap, ScreenRectIsTheLinesOfTheAreaAndHoldsWhatTheRegionHolds) {
  Fixture f;
  const RegionMap map = RegionMap::grid({0, 20, 40, 64}, {0, 16, 48}, f.lines);
  const ScreenRect middle = map.screenRectOf(1), corner = map.screenRectOf(5);
  EXPECT_EQ(middle.s0, f.lines.at(0, 20));
  EXPECT_EQ(middle.s1, f.lines.at(0, 40));
  EXPECT_EQ(middle.q0, -core::kInfinity);
  EXPECT_EQ(middle.q1, f.lines.at(1, 16));
  EXPECT_EQ(corner.s1, core::kInfinity);
  EXPECT_EQ(corner.q1, core::kInfinity);
  std::mt19937 random(7);
  int inside = 0;
  for (int k = 0; k < 2000; ++k) {
    const EyeFrameRay er = EyeFrameRay::of(rayNearTheMiddle(random), f.view);
    const double t = 0.5;
    if (!er.inFront(t)) continue;
    const int owner = map.ownerAt(er, t);
    for (int id = 0; id < map.processors(); ++id) {
      const ScreenRect r = map.screenRectOf(id);
      const double s = er.screenAt(0, t), q = er.screenAt(1, t);
      const bool inRect = s >= r.s0 && s < r.s1 && q >= r.q0 && q < r.q1;
      EXPECT_EQ(map.holds(id, er, t), inRect);
      EXPECT_EQ(inRect, id == owner);
    }
    inside += owner == 1;
  }
  EXPECT_GT(inside, 0);
}

// Where a ray leaving a region goes: on a uniform grid the next cell across the faces it crosses (corners
// included), the very processor the same areas name when looked up as an arbitrary tiling.
TEST(RegionMap, GridNamesTheOwnerBeyondAnExitAsTheGeneralLookupDoes) {
  Fixture f;
  const std::vector<int> columns{0, 20, 40, 64}, rows{0, 16, 30, 48};
  const RegionMap grid = RegionMap::grid(columns, rows, f.lines);
  const RegionMap tiling(RegionMap::gridAreas(columns, rows), f.lines);  // no grid shortcut
  ASSERT_GT(grid.gridColumns(), 0);
  ASSERT_EQ(tiling.gridColumns(), 0);
  std::mt19937 random(11);
  int exits = 0;
  for (int id = 0; id < grid.processors(); ++id) {
    const RegionCells cells(grid.areaOf(id), f.lines, 0, false, f.all, f.boxes);
    for (int n = 0; n < 400; ++n) {
      const EyeFrameRay er = EyeFrameRay::of(rayNearTheMiddle(random), f.view);
      if (!er.inFront(0) || grid.ownerAt(er, 0) != id) continue;
      int i, j;
      cells.locate(er, 0, i, j);
      RegionExit exit;
      std::uint64_t steps = 0;
      auto everyCell = [](double, double, const std::vector<std::uint32_t>&) { return true; };
      if (cells.walk(er, 0, er.partEnd(0), i, j, everyCell, exit, steps) != WalkResult::Exited) continue;
      ++exits;
      EXPECT_EQ(grid.ownerBeyond(id, er, exit.t, exit.sStep, exit.qStep),
                tiling.ownerBeyond(id, er, exit.t, exit.sStep, exit.qStep))
          << "region " << id << ", exit (" << exit.sStep << ", " << exit.qStep << ") at t " << exit.t;
    }
  }
  EXPECT_GT(exits, 300);
  // Through a corner (rare on random rays) the ray meets the diagonal region: region 4, in the middle of
  // the 3 x 3 grid, to 8 and to 0.
  for (int step : {1, -1}) {
    const int diagonal = step > 0 ? 8 : 0;
    EXPECT_EQ(grid.ownerBeyond(4, EyeFrameRay{}, 0, step, step), diagonal);
    EXPECT_EQ(tiling.ownerBeyond(4, EyeFrameRay{}, 0, step, step), diagonal);
  }
}

// Figure 10: after a BSP a region borders several others on one face; routes follow the adjacency graph.
TEST(RegionMap, ArbitraryTilingHasItsAdjacencyGraphAndShortestRoutes) {
  Fixture f;
  // 0 | 1        0: left half; 1, 2: right half split in rows; 3: bottom strip under 0 only
  //   | 2
  // 3 |
  const RegionMap map({{0, 32, 0, 30}, {32, 64, 0, 20}, {32, 64, 20, 48}, {0, 32, 30, 48}}, f.lines);
  EXPECT_EQ(map.neighbours(0), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(map.neighbours(1), (std::vector<int>{0, 2}));
  EXPECT_EQ(map.neighbours(3), (std::vector<int>{0, 2}));
  EXPECT_EQ(map.faceToward(0, 1), Face::Right);
  EXPECT_EQ(map.faceToward(0, 2), Face::Right);
  EXPECT_EQ(map.nextHop(1, 3) == 0 || map.nextHop(1, 3) == 2, true);
  EXPECT_EQ(map.nextHop(3, 1) == 0 || map.nextHop(3, 1) == 2, true);
  EXPECT_THROW(RegionMap({{0, 32, 0, 48}, {30, 64, 0, 48}}, f.lines), std::invalid_argument);  // overlap
  EXPECT_THROW(RegionMap({{0, 32, 0, 48}}, f.lines), std::invalid_argument);                   // a hole
}

}  // namespace
}  // namespace raycube::node
