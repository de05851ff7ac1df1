// The message-passing machine (host/machine/machine_settings.h) renders exactly what the one-thread reference
// renders, bit for bit, whatever the processor grid and FIFO capacity: every ray is spawned once and finished
// once, every contribution reaches the host, eye rays never leave their processor (3.1), and the space behind
// the eye plane, which no pyramid covers, is traced too.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "core/image.h"
#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "core/view.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "host/report/machine_stats.h"
#include "machine_test_support.h"
#include "node/eye_box.h"

namespace raycube::host {
namespace {

using namespace testing_support;

struct Grid {
  int rows, columns;
};

std::string gridName(Grid g) {
  return std::to_string(g.rows) + "x" + std::to_string(g.columns);
}

// Light rays travel as messages unless a test says otherwise: the heaviest traffic, the strictest test of
// the walk across regions. Light-ray deletion (cone, pyramid) has its own tests below.
MachineSettings machineFor(Grid grid, std::size_t capacity,
                           node::LightRayMode lightRays = node::LightRayMode::Messages) {
  return uniformGrid(grid.rows, grid.columns, capacity, lightRays);
}

// ---------------------------------------------------------------------------------------------------------
// 1-3: bit identity, conservation, no eye-ray messages, on every shipped scene.

const std::vector<Grid>& allGrids() {
  static const std::vector<Grid> grids{{1, 1}, {2, 2}, {4, 4}, {8, 8}, {3, 5}};
  return grids;
}

TEST(MachineTest, Balls2MatchesReferenceOnEveryGridAndCapacity) {
  const core::Scene scene = core::makeBalls(2);
  const int side = sanitized() ? 16 : 40;
  const RenderSettings settings = settingsFor(side);
  const RenderResult reference = renderReference(scene, settings);
  ASSERT_GT(reference.counters.of(core::RayKind::Reflected), 0u);
  ASSERT_GT(reference.counters.of(core::RayKind::Light), 0u);
  std::vector<Grid> grids = allGrids();
  std::vector<std::size_t> capacities{1, 8, 128};
  if (sanitized()) {
    grids = {{1, 1}, {3, 5}, {8, 8}};
    capacities = {1, 8};
  }
  for (Grid g : grids)
    for (std::size_t capacity : capacities)
      renderAndCompare(
          scene, reference, settings, machineFor(g, capacity),
          "balls2 " + std::to_string(side) + "px " + gridName(g) + " capacity " + std::to_string(capacity));
}

// 3.7.2: with light cones or pyramids every light ray is traced where it starts, and nothing changes.
TEST(MachineTest, LightConesAndPyramidsDeleteLightRayMessagesAndKeepTheImage) {
  for (const char* name : {"balls2", "gears1", "teapot2"}) {
    const core::Scene scene = std::string(name) == "balls2"
                                  ? core::makeBalls(2)
                                  : core::readNff(testing_support::scenePath(std::string(name) + ".nff"));
    const int side = sanitized() ? 16 : 32;
    const RenderSettings settings = settingsFor(side);
    const RenderResult reference = renderReference(scene, settings);
    for (node::LightRayMode mode : {node::LightRayMode::Cone, node::LightRayMode::Pyramid}) {
      for (Grid g : std::vector<Grid>{{1, 1}, {4, 4}, {3, 5}}) {
        for (std::size_t capacity : {std::size_t(1), std::size_t(128)}) {
          const std::string label = std::string(name) +
                                    (mode == node::LightRayMode::Cone ? " cone " : " pyramid ") +
                                    gridName(g) + " capacity " + std::to_string(capacity);
          MachineReport report;
          const RenderResult result =
              renderMachineWatched(scene, settings, machineFor(g, capacity, mode), report, label);
          expectMachineMatchesReference(reference, result, report, label);
          std::uint64_t lightMessages = 0, tracedHere = 0;
          for (const ProcessorReport& p : report.processors) {
            lightMessages += p.node.messagesByKind[std::size_t(core::RayKind::Light)];
            tracedHere += p.node.lightRaysTracedLocally;
          }
          EXPECT_EQ(lightMessages, 0u) << label;
          EXPECT_EQ(tracedHere, reference.counters.of(core::RayKind::Light)) << label;
        }
      }
    }
  }
}

// Figure 11: a light among the objects. As messages its light rays converge on the processors around it;
// with light pyramids (which degenerate to "every object" where the light lies among a region's sources)
// there are none, and the image does not change.
TEST(MachineTest, LightAmongTheObjectsSendsLightRaysOnlyAsMessages) {
  const core::Scene scene = core::readNff(testing_support::scenePath("lamp_among_balls.nff"));
  const RenderSettings settings = settingsFor(sanitized() ? 16 : 48);
  const RenderResult reference = renderReference(scene, settings);
  std::uint64_t lightMessages[2] = {};
  int k = 0;
  for (node::LightRayMode mode : {node::LightRayMode::Messages, node::LightRayMode::Pyramid}) {
    MachineReport report;
    const std::string label = std::string("lamp among balls ") + (k == 0 ? "messages" : "pyramid");
    const RenderResult result =
        renderMachineWatched(scene, settings, machineFor({4, 4}, 8, mode), report, label);
    expectMachineMatchesReference(reference, result, report, label);
    for (const ProcessorReport& p : report.processors)
      lightMessages[k] += p.node.messagesByKind[std::size_t(core::RayKind::Light)];
    ++k;
  }
  EXPECT_GT(lightMessages[0], 100u);
  EXPECT_EQ(lightMessages[1], 0u);
}

// The pyramid fits a region's light volume at least as tightly as the cone (3.7.2), processor by processor.
TEST(MachineTest, PyramidHoldsNoMoreObjectsThanCone) {
  const core::Scene scene = core::makeBalls(3);
  const RenderSettings settings = settingsFor(24);
  MachineReport cone, pyramid;
  renderMachine(scene, settings, machineFor({4, 4}, 128, node::LightRayMode::Cone), &cone);
  renderMachine(scene, settings, machineFor({4, 4}, 128, node::LightRayMode::Pyramid), &pyramid);
  std::size_t coneTotal = 0, pyramidTotal = 0;
  for (std::size_t p = 0; p < cone.processors.size(); ++p) {
    coneTotal += cone.processors[p].node.lightObjects;
    pyramidTotal += pyramid.processors[p].node.lightObjects;
  }
  EXPECT_LE(pyramidTotal, coneTotal);
  EXPECT_GT(coneTotal, 0u);
}

TEST(MachineTest, Balls2CornerSamplingMatchesReference) {
  const core::Scene scene = core::makeBalls(2);
  const int side = sanitized() ? 16 : 40;
  const RenderSettings settings = settingsFor(side, core::Sampling::Corners);
  const RenderResult reference = renderReference(scene, settings);
  for (std::size_t capacity : {std::size_t(1), std::size_t(8)})
    renderAndCompare(
        scene, reference, settings, machineFor({3, 5}, capacity),
        "balls2 corners " + std::to_string(side) + "px 3x5 capacity " + std::to_string(capacity));
  if (!sanitized())  // 41 x 41 samples: a 41 x 41 grid gives every processor a single eye ray
    renderAndCompare(scene, reference, settings, machineFor({8, 8}, 1), "balls2 corners 8x8 capacity 1");
}

struct SceneCase {
  std::string file;
  int side;  // image side: smaller for the big databases
};

std::string sceneCaseName(const testing::TestParamInfo<SceneCase>& info) {
  return info.param.file.substr(0, info.param.file.find('.'));
}

class MachineSceneTest : public testing::TestWithParam<SceneCase> {};

// All grids at capacity 8, plus the tightest FIFOs on the largest grid.
TEST_P(MachineSceneTest, MatchesReference) {
  const SceneCase& c = GetParam();
  const core::Scene scene = core::readNff(testing_support::scenePath(c.file));
  const int side = sanitized() ? 16 : c.side;
  const RenderSettings settings = settingsFor(side);
  const RenderResult reference = renderReference(scene, settings);
  std::vector<std::pair<Grid, std::size_t>> runs;
  if (sanitized()) {
    runs = {{{3, 5}, 8}, {{8, 8}, 1}};
  } else {
    for (Grid g : allGrids()) runs.push_back({g, 8});
    runs.push_back({{8, 8}, 1});
  }
  for (const auto& [grid, capacity] : runs)
    renderAndCompare(scene, reference, settings, machineFor(grid, capacity),
                     c.file + " " + std::to_string(side) + "px " + gridName(grid) + " capacity " +
                         std::to_string(capacity));
  // The same with float rays: another image, but the same one everywhere.
  RenderSettings floats = settings;
  floats.precision = core::Precision::Float;
  const RenderResult floatReference = renderReference(scene, floats);
  EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, floats).image, floatReference.image))
      << c.file << " float image-parallel";
  for (const auto& [grid, capacity] : {std::pair{Grid{3, 5}, 8}, std::pair{Grid{8, 8}, 1}})
    renderAndCompare(scene, floatReference, floats, machineFor(grid, std::size_t(capacity)),
                     c.file + " float " + gridName(grid) + " capacity " + std::to_string(capacity));
}

std::vector<SceneCase> sceneCases() {
  const std::map<std::string, int> sides{{"balls1.nff", 40},  {"balls2.nff", 40}, {"balls3.nff", 32},
                                         {"balls4.nff", 24},  {"gears1.nff", 32}, {"jacks1.nff", 40},
                                         {"teapot2.nff", 32}, {"tree1.nff", 40}};
  std::vector<SceneCase> cases;
  for (const auto& entry : std::filesystem::directory_iterator(testing_support::sourcePath("scenes")))
    if (entry.path().extension() == ".nff") {
      const std::string file = entry.path().filename().string();
      const auto side = sides.find(file);
      cases.push_back({file, side == sides.end() ? 24 : side->second});
    }
  std::sort(cases.begin(), cases.end(),
            [](const SceneCase& a, const SceneCase& b) { return a.file < b.file; });
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Scenes, MachineSceneTest, testing::ValuesIn(sceneCases()), sceneCaseName);

TEST(MachineTest, EveryShippedSceneIsTested) {
  std::vector<std::string> files;
  for (const SceneCase& c : sceneCases()) files.push_back(c.file);
  for (const char* expected : {"balls1.nff", "balls2.nff", "balls3.nff", "balls4.nff", "gears1.nff",
                               "jacks1.nff", "teapot2.nff", "tree1.nff"})
    EXPECT_NE(std::find(files.begin(), files.end(), expected), files.end()) << expected << " is missing";
}

// ---------------------------------------------------------------------------------------------------------
// 6-7: the space behind the eye plane, objects straddling it, an eye inside a transparent sphere.

// A mirror sphere (Ks = 1) in front of the camera; `behind` adds a red sphere behind the camera, which only
// reflected rays travelling behind the eye plane can see.
std::string mirrorScene(bool behind) {
  std::string nff =
      "b 0.1 0.1 0.3\n"
      "v\n"
      "from 0 0 5\n"
      "at 0 0 0\n"
      "up 0 1 0\n"
      "angle 40\n"
      "hither 0.01\n"
      "resolution 32 32\n"
      "l 4 6 8\n"
      "f 0.9 0.9 0.9 0 1 100 0 1\n"
      "s 0 0 0 1.4\n";
  if (behind)
    nff +=
        "f 1 0.2 0.1 1 0 0 0 1\n"
        "s 0 0 11 3\n";
  return nff;
}

TEST(MachineTest, ReflectionsBehindTheEyeMatchReference) {
  const core::Scene withRear = core::parseNff(mirrorScene(true), "mirror_behind.nff");
  const core::Scene without = core::parseNff(mirrorScene(false), "mirror_alone.nff");
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsFor(side);
  // The red sphere lies wholly behind the eye plane: no pyramid holds it, every processor does.
  const core::View view(withRear.camera, side, side, settings.sampling);
  ASSERT_TRUE(
      node::reachesBehindEye(node::eyeBoxOf(withRear.objects[1], view, 2 * withRear.largestCoordinate())));

  const RenderResult reference = renderReference(withRear, settings);
  const RenderResult referenceWithout = renderReference(without, settings);
  // The test can fail: the object behind the camera shows in the mirror.
  ASSERT_FALSE(core::bitIdentical(reference.image, referenceWithout.image));
  EXPECT_GT(core::compareImages(reference.image, referenceWithout.image).pixelsOver, 2u);

  for (Grid g : {Grid{1, 1}, Grid{2, 2}, Grid{3, 5}, Grid{8, 8}})
    for (std::size_t capacity : {std::size_t(1), std::size_t(8)}) {
      const std::string label = "mirror+rear sphere " + gridName(g) + " capacity " + std::to_string(capacity);
      MachineReport report;
      const RenderResult machine =
          renderMachineWatched(withRear, settings, machineFor(g, capacity), report, label);
      expectMachineMatchesReference(reference, machine, report, label);
      EXPECT_FALSE(core::bitIdentical(machine.image, referenceWithout.image)) << label;
      for (const ProcessorReport& p : report.processors) EXPECT_EQ(p.node.rearObjects, 1u) << label;
    }
}

// A ground reaching behind the eye, a sphere in front, a light far in front, and a row of pebbles above
// the view, off every segment from a visible point to the light but on segments from the ground behind the
// eye to it; `groundKs` makes the ground a mirror.
std::string pebblesAboveTheView(double groundKs) {
  std::string nff =
      "b 0.1 0.1 0.3\nv\nfrom 0 1 5\nat 0 1 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 32 32\n"
      "l 0 10 -20\n";
  nff += "f 0.8 0.8 0.8 0.8 " + std::to_string(groundKs) + " 10 0 1\n";
  nff += "p 4\n-20 0 -20\n-20 0 20\n20 0 20\n20 0 -20\n";
  nff += "f 0.9 0.3 0.3 0.9 0 10 0 1\ns 0 1 0 1\n";
  for (int i = 0; i < 12; ++i) nff += "s " + std::to_string(-3 + 0.5 * i) + " 4 0 0.2\n";
  return nff;
}

// Without reflected or refracted rays, only eye rays meet objects, always in front of the eye: the parts of
// objects behind it start no light ray, so their light volumes add nothing to what a processor holds. With
// a mirror ground they do (light rays start on the ground behind the eye, where reflections land).
TEST(MachineTest, MatteScenesHoldNoLightVolumeBehindTheEye) {
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsFor(side);
  std::size_t held[2] = {};
  for (int mirror = 0; mirror < 2; ++mirror) {
    const core::Scene scene = core::parseNff(pebblesAboveTheView(mirror ? 0.5 : 0), "pebbles.nff");
    const core::View view(scene.camera, side, side, settings.sampling);
    ASSERT_TRUE(
        node::reachesBehindEye(node::eyeBoxOf(scene.objects[0], view, 2 * scene.largestCoordinate())));
    const std::string label = mirror ? "pebbles, mirror ground" : "pebbles, matte ground";
    const RenderResult reference = renderReference(scene, settings);
    MachineReport report;
    const RenderResult machine = renderMachineWatched(
        scene, settings, machineFor({4, 4}, 8, node::LightRayMode::Pyramid), report, label);
    expectMachineMatchesReference(reference, machine, report, label);
    for (const ProcessorReport& p : report.processors) held[mirror] += p.node.heldObjects;
  }
  EXPECT_LT(held[0], held[1]);
}

TEST(MachineTest, BallsFloorReachesBehindTheEye) {
  // balls: eye at (2.1, 1.3, 1.7), floor polygon +-12 at z = -0.5: most of the floor is behind the eye plane.
  const core::Scene scene = core::makeBalls(2);
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsFor(side);
  const core::View view(scene.camera, side, side, settings.sampling);
  ASSERT_TRUE(std::holds_alternative<core::Polygon>(scene.objects[0].shape));
  EXPECT_TRUE(node::reachesBehindEye(node::eyeBoxOf(scene.objects[0], view, 2 * scene.largestCoordinate())));
  const RenderResult reference = renderReference(scene, settings);
  MachineReport report;
  const RenderResult machine =
      renderMachineWatched(scene, settings, machineFor({4, 4}, 4), report, "balls2 4x4");
  expectMachineMatchesReference(reference, machine, report, "balls2 4x4 capacity 4");
  for (const ProcessorReport& p : report.processors) EXPECT_GE(p.node.rearObjects, 1u);
}

// A floor polygon through the eye plane, a big sphere straddling it off to the side (seen at the image's
// right edge and in the mirror), a mirror sphere in front.
const char* kStraddlingScene =
    "b 0.1 0.1 0.3\n"
    "v\n"
    "from 0 0 5\n"
    "at 0 0 0\n"
    "up 0 1 0\n"
    "angle 60\n"
    "hither 0.01\n"
    "resolution 32 32\n"
    "l 3 8 2\n"
    "l -6 4 12\n"
    "f 0.8 0.8 0.8 0.2 0.8 50 0 1\n"
    "s 0 0 0 1\n"
    "f 0.2 0.8 0.3 0.9 0.1 10 0 1\n"
    "s 2 0 5 1.8\n"
    "f 0.9 0.7 0.4 0.8 0.2 10 0 1\n"
    "p 4\n"
    "20 -1.5 20\n"
    "20 -1.5 -20\n"
    "-20 -1.5 -20\n"
    "-20 -1.5 20\n";

TEST(MachineTest, ObjectsStraddlingTheEyePlaneMatchReference) {
  const core::Scene scene = core::parseNff(kStraddlingScene, "straddling.nff");
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsFor(side);
  const core::View view(scene.camera, side, side, settings.sampling);
  for (std::size_t o : {std::size_t(1), std::size_t(2)})
    ASSERT_TRUE(node::reachesBehindEye(node::eyeBoxOf(scene.objects[o], view, 2 * scene.largestCoordinate())))
        << "object " << o;
  const RenderResult reference = renderReference(scene, settings);
  for (Grid g : {Grid{1, 1}, Grid{2, 2}, Grid{3, 5}, Grid{8, 8}})
    for (std::size_t capacity : {std::size_t(1), std::size_t(8)})
      renderAndCompare(scene, reference, settings, machineFor(g, capacity),
                       "straddling " + gridName(g) + " capacity " + std::to_string(capacity));
}

// The eye inside a clear sphere (T = 1, Kd = 0): every eye ray starts inside an object and leaves it through
// the back; with ior 1.5 it bends there. A mirror sphere and a floor give the refracted rays something to
// hit.
// Background, camera (the eye at z = 5, inside the clear sphere) and light of both eye-inside scenes.
const std::string kEyeInsideView =
    "b 0.1 0.1 0.3\n"
    "v\n"
    "from 0 0 5\n"
    "at 0 0 0\n"
    "up 0 1 0\n"
    "angle 45\n"
    "hither 0.01\n"
    "resolution 32 32\n"
    "l 3 8 2\n";

std::string eyeInsideScene(const std::string& ior) {
  return kEyeInsideView + "f 1 1 1 0 0.1 30 1 " + ior +
         "\n"
         "s 0 0 5 1.2\n"
         "f 0.8 0.8 0.8 0.3 0.7 50 0 1\n"
         "s 0 0 0 1\n"
         "f 0.9 0.7 0.4 0.8 0.2 10 0 1\n"
         "p 4\n"
         "20 -1.5 20\n"
         "20 -1.5 -20\n"
         "-20 -1.5 -20\n"
         "-20 -1.5 20\n";
}

TEST(MachineTest, EyeInsideTransparentSphereMatchesReference) {
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsFor(side);
  for (const std::string ior : {"1.0", "1.5"}) {
    const core::Scene scene = core::parseNff(eyeInsideScene(ior), "eye_inside.nff");
    const RenderResult reference = renderReference(scene, settings);
    ASSERT_GT(reference.counters.of(core::RayKind::Refracted), 0u) << "ior " << ior;
    for (Grid g : {Grid{1, 1}, Grid{2, 2}, Grid{3, 5}, Grid{8, 8}})
      for (std::size_t capacity : {std::size_t(1), std::size_t(8)})
        renderAndCompare(
            scene, reference, settings, machineFor(g, capacity),
            "eye inside sphere ior " + ior + " " + gridName(g) + " capacity " + std::to_string(capacity));
  }
}

// The smallest form of the scene above that the machine got wrong (found by this suite): purely diffuse
// materials, so the only secondary rays are the clear sphere's refracted rays (and light rays). Pixels
// (13, 26) and (18, 26) of a 32 x 32 image: the refracted ray passes near the diffuse sphere and should hit
// the floor; one processor is enough, so it is the region's cell walk, not the messages.
TEST(MachineTest, EyeInsideRefractingSphereOneProcessorMatchesReference) {
  const std::string nff = kEyeInsideView +
                          "f 1 1 1 0 0 30 1 1.5\n"
                          "s 0 0 5 1.2\n"
                          "f 0.8 0.8 0.8 0.3 0 50 0 1\n"
                          "s 0 0 0 1\n"
                          "f 0.9 0.7 0.4 0.8 0 10 0 1\n"
                          "s 0 -101.5 0 100\n";
  const core::Scene scene = core::parseNff(nff, "eye_inside_minimal.nff");
  const RenderSettings settings = settingsFor(32);
  const RenderResult reference = renderReference(scene, settings);
  renderAndCompare(scene, reference, settings, machineFor({1, 1}, 8), "eye inside minimal 32px 1x1");
}

// ---------------------------------------------------------------------------------------------------------
// 8: a grid the sample grid cannot feed is a user error, named by its option.

// The preprocessing time is accounted for phase by phase (3.2 steps 1-2, 3.7.1): the phases lie inside it,
// one after the other; the hypercube embedding is worked out during the synthesis unless emulating, and the
// report says which.
TEST(MachineTest, PreprocessingPhasesLieWithinThePreprocessingTime) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings machine = machineFor({4, 4}, 8);
  machine.balance = Balance::Bsp;
  machine.mapHypercube = true;
  MachineReport report;
  const RenderResult result = renderMachine(scene, settingsFor(32), machine, &report);
  const PreprocessingSeconds& pre = report.preprocessing;
  for (double phase : {pre.sampling, pre.partitioning, pre.pruning, pre.cells, pre.mapping})
    EXPECT_GT(phase, 0);
  EXPECT_LE(pre.sampling + pre.partitioning + pre.pruning + pre.cells, result.preprocessSeconds);
  const nlohmann::json json = machineJson(report).at("preprocessingSeconds");
  EXPECT_EQ(json.at("pruning").get<double>(), pre.pruning);
  EXPECT_TRUE(json.at("mappingDuringSynthesis").get<bool>());
  EXPECT_NE(machineTable(report).find("hypercube mapping"), std::string::npos);
}

// Only the emulated machine's links need the hypercube embedding: a run that does not ask for it in its
// report skips it (the BSP's heuristic is a tenth of a second of CPU at 8 x 8) and says so, with the same
// image.
TEST(MachineTest, HypercubeMappedOnlyWhenAskedOrEmulated) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings machine = machineFor({4, 4}, 8);
  machine.balance = Balance::Bsp;
  machine.mapHypercube = true;
  MachineReport mapped, unmapped;
  const RenderResult withMap = renderMachine(scene, settingsFor(32), machine, &mapped);
  machine.mapHypercube = false;
  const RenderResult withoutMap = renderMachine(scene, settingsFor(32), machine, &unmapped);
  EXPECT_EQ(mapped.hypercubeNode.size(), 16u);
  EXPECT_GT(mapped.dilationMean, 0);
  EXPECT_TRUE(unmapped.hypercubeNode.empty());
  EXPECT_NE(machineTable(unmapped).find("hypercube not mapped"), std::string::npos);
  EXPECT_FALSE(machineJson(unmapped).at("hypercube").at("mapped").get<bool>());
  EXPECT_FALSE(machineJson(unmapped).at("preprocessingSeconds").at("mappingDuringSynthesis").get<bool>());
  EXPECT_EQ(unmapped.preprocessing.mapping, 0);
  EXPECT_TRUE(withMap.image.pixels == withoutMap.image.pixels);
}

// The FIFO's capacity: the one asked for, else the engine's own (512 rays on threads, the iPSC's 128 in
// emulated time and over MPI); a run's summary and stats name the capacity it used.
TEST(MachineTest, FifoCapacityIsTheEnginesUnlessAsked) {
  MachineSettings machine;
  EXPECT_EQ(fifoRaysFor(machine), node::scheduling::kThreadsFifoRays);
  EXPECT_EQ(node::scheduling::kThreadsFifoRays, 512u);
  machine.mpi = true;
  EXPECT_EQ(fifoRaysFor(machine), 128u);
  machine.mpi = false;
  machine.emulate = builtinPlatform("ipsc1");
  EXPECT_EQ(fifoRaysFor(machine), 128u);
  machine.queueCapacity = 7;
  EXPECT_EQ(fifoRaysFor(machine), 7u);

  const core::Scene scene = core::makeBalls(1);
  MachineSettings threads = machineFor({2, 2}, 1);
  threads.queueCapacity.reset();
  MachineReport report;
  renderMachine(scene, settingsFor(16), threads, &report);
  EXPECT_EQ(report.settings.queueCapacity, std::optional<std::size_t>(512));
  EXPECT_NE(machineTable(report).find("FIFO 512 rays"), std::string::npos) << machineTable(report);
  EXPECT_EQ(machineJson(report).at("queueCapacity").get<std::size_t>(), 512u);
}

// A ray leaving its region beyond the scene's bounds ends there: fewer messages, the same image, every ray
// still finished once; with the paper's rays (as the emulated machine has them) none ends early.
TEST(MachineTest, RaysLeavingTheSceneEndWhereTheyLeaveIt) {
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = settingsFor(32);
  const RenderResult reference = renderReference(scene, settings);
  auto messages = [](const MachineReport& r) {
    std::uint64_t sent = 0, leftScene = 0;
    for (const ProcessorReport& p : r.processors) {
      for (std::uint64_t m : p.node.messagesByKind) sent += m;
      leftScene += p.node.leftScene;
    }
    return std::pair{sent, leftScene};
  };
  for (node::LightRayMode light : {node::LightRayMode::Messages, node::LightRayMode::Pyramid}) {
    MachineSettings machine = machineFor({4, 4}, 8);
    machine.lightRays = light;
    MachineReport ending, travelling;
    const RenderResult ended = renderMachine(scene, settings, machine, &ending);
    machine.endRaysLeavingScene = false;
    const RenderResult travelled = renderMachine(scene, settings, machine, &travelling);
    EXPECT_TRUE(core::bitIdentical(ended.image, reference.image));
    EXPECT_TRUE(core::bitIdentical(travelled.image, reference.image));
    EXPECT_EQ(ended.counters.rays, reference.counters.rays);
    EXPECT_EQ(travelled.counters.rays, reference.counters.rays);
    const auto [sentEnding, leftEnding] = messages(ending);
    const auto [sentTravelling, leftTravelling] = messages(travelling);
    EXPECT_GT(leftEnding, 0u);
    EXPECT_EQ(leftTravelling, 0u);
    EXPECT_LT(sentEnding, sentTravelling);
  }
}

// A ray inside a glass sphere crosses many regions: the nearest hit a region finds beyond its part of the
// ray travels with it (BasicRayMessage::ahead), so the regions ahead take it instead of testing the sphere
// again. The machine then tests spheres about as often as image-parallel does, where testing them afresh
// in every region cost it a third more (32 and 48 pixels, tried); and renders the same image.
TEST(MachineTest, TheNearestHitFoundAheadTravelsWithTheRay) {
  const core::Scene scene = core::readNff(testing_support::scenePath("mount6.nff"));  // 4 glass spheres
  const RenderSettings settings = settingsFor(sanitized() ? 32 : 64);
  const RenderResult imageParallel = renderImageParallel(scene, settings);
  MachineSettings machine = uniformGrid(8, 8, 128, node::LightRayMode::Pyramid);
  machine.cells = node::CellStructure::Bvh;
  const RenderResult result = renderMachine(scene, settings, machine);
  EXPECT_TRUE(core::bitIdentical(result.image, imageParallel.image));
  const auto sphereTests = [](const RenderResult& r) { return double(r.counters.testsByShape[0]); };
  ASSERT_GT(sphereTests(imageParallel), 0);
  EXPECT_LT(sphereTests(result), 1.15 * sphereTests(imageParallel));
}

TEST(MachineTest, MoreProcessorsThanSampleRowsOrColumnsThrows) {
  const core::Scene scene = core::makeBalls(1);
  const RenderSettings settings = settingsFor(8);
  for (Grid g : {Grid{10, 10}, Grid{9, 1}, Grid{1, 9}}) {
    try {
      renderMachine(scene, settings, machineFor(g, 8));
      ADD_FAILURE() << gridName(g) << " processors on an 8x8 image: no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--procs"), std::string::npos) << e.what();
    }
  }
  // Corner sampling has 9 x 9 samples on an 8 x 8 image: 9 x 9 processors are fine, 10 x 10 are not.
  const RenderSettings corners = settingsFor(8, core::Sampling::Corners);
  EXPECT_THROW(renderMachine(scene, corners, machineFor({10, 10}, 8)), std::invalid_argument);
  const RenderResult reference = renderReference(scene, corners);
  renderAndCompare(scene, reference, corners, machineFor({9, 9}, 1), "balls1 corners 8px 9x9 capacity 1");
  // A degenerate grid or FIFO is refused too.
  EXPECT_THROW(renderMachine(scene, settings, machineFor({0, 2}, 8)), std::invalid_argument);
  EXPECT_THROW(renderMachine(scene, settings, machineFor({2, 2}, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace raycube::host
