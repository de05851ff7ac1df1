// Hostile scenes found by differential fuzzing (issue 41): whatever the numbers, no walk loops, no engine
// spins, and every mode draws the reference's image.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include "core/image.h"
#include "core/intersect.h"
#include "core/nff_reader.h"
#include "core/precision.h"
#include "host/machine/emulated_platform.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"
#include "test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

RenderSettings sixteen(core::Precision precision) {
  RenderSettings s;
  s.width = s.height = 16;
  s.progress = false;
  s.precision = precision;
  return s;
}

// A red sphere under one light: for the watchdogs' tests, whose machines stall whatever they render.
core::Scene oneSphere(const std::string& name) {
  return core::parseNff(
      "v\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 30\nhither 0.001\nresolution 8 8\n"
      "l 3 4 -5\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n",
      name);
}

// Every machine configuration the differential fuzzer runs (tests/fuzz/differential_oracle.cpp).
std::vector<std::pair<std::string, MachineSettings>> machines() {
  MachineSettings bsp;
  bsp.rows = bsp.columns = 2;
  bsp.balance = Balance::Bsp;
  bsp.lightRays = node::LightRayMode::Messages;
  MachineSettings paper = uniformGrid(2, 2, 512);
  paper.cells = node::CellStructure::Paper;
  return {{"2x2 uniform", uniformGrid(2, 2, 512)},
          {"2x2 bsp, light rays as messages", bsp},
          {"2x2 uniform, paper cells", paper}};
}

// In both precisions, at 16x16.
void expectEveryModeDrawsTheReference(const core::Scene& scene) {
  for (const core::Precision precision : {core::Precision::Float, core::Precision::Double}) {
    SCOPED_TRACE(core::nameOf(precision));
    const RenderSettings settings = sixteen(precision);
    const core::Image reference = renderReference(scene, settings).image;
    EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, settings).image, reference))
        << "image-parallel";
    for (const auto& [label, machine] : machines()) {
      MachineReport report;
      const RenderResult result = renderMachineWatched(scene, settings, machine, report, label);
      EXPECT_TRUE(core::bitIdentical(result.image, reference)) << label;
    }
  }
}

// Class 1: a sphere of radius 6e7 in float sends light rays of NaN; the float machine's walk asked for the
// ray's next part forever (a NaN tMax ends no part), at 100% CPU. Now every walk is bounded.
TEST(HostileScenes, ALightRayOfNaNEndsInEveryMode) {
  const core::Scene scene = core::parseNff(
      "v\nfrom 1 3 7\nat 0 0 0\nup 0 0 1\nangle 45\nhither 0\nresolution 3 2\nl 1 -4  5\n"
      "f 1 0 3 0 5 7 0 1\ns 0 0 0 5\ns 4 0 .5 60617284",
      "nan_light_ray.nff");
  expectEveryModeDrawsTheReference(scene);
}

// Class 2: a quadrilateral whose fourth vertex leaves the plane of the others (NFF files carry such
// rounding-level non-planarity, and worse). Hits lie on the polygon's plane, off the box of its vertices: the
// BVHs culled them, the reference found them (168 reflected rays against 166). Every box now holds the
// plane's points over the vertices.
TEST(HostileScenes, ANonPlanarPolygonIsHitAlikeInEveryMode) {
  const core::Scene scene = core::parseNff(
      "v\nfrom 4.86 7.2 5.4\nat 0 0 0\nup 0 0 1\nangle 45\nhither 0.01\nresolution 16 16\n"
      "l 3 4 10\nl -5 2 8\nf 1 0.5 0.5 0.5 0.5 10 0 0\n"
      "p 4\n-4 0 5\n0 2 0\n0 4 0\n-4 4 0\np 4\n0 0 0\n4 0 0\n4 4 0\n0 4 0\n",
      "non_planar.nff");
  // Every hit on the lifted polygon, over a fan of rays from the eye, lies in its box (padded as the BVH's).
  const core::Box box = core::boundsOf(scene.objects[0], core::kBoxPaddingRelative);
  const core::Vec3 eye(4.86, 7.2, 5.4);
  int hits = 0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const core::Vec3 target(-6 + 0.2 * i, -2 + 0.2 * j, 0);
      const core::BasicRay<double> ray{eye, glm::normalize(target - eye), 0, core::kInfinity};
      const double t = core::nearestHit(scene.objects[0], ray, core::kInfinity);
      if (t == core::kInfinity) continue;
      ++hits;
      EXPECT_TRUE(box.holds(ray.at(t))) << "hit off the box towards " << i << ", " << j;
    }
  EXPECT_GT(hits, 100);
  expectEveryModeDrawsTheReference(scene);
}

// Found by the structure-aware campaign: a cylinder 37,708 units long and 0.07 wide, seen in float near one
// end, far from its middle. The quadratic's noise put a root off the cylinder and its box; the BVHs culled
// it, the reference drew it. A cone's root is a hit only inside the box every structure tests.
TEST(HostileScenes, ALongThinFloatCylinderIsHitAlikeInEveryMode) {
  const core::Scene scene = core::parseNff(
      "v\nfrom -1 -2.61313 0.5\nat -1 -1.61313 0.5\nup 0 0 1\nangle 45\nhither 1\nresolution 8 8\n"
      "l 2 -2.61313 -4\nf 1 1 1 1 0 100000 0 0\n"
      "p 4\n2.27965 5.22625 3.77965\n-4.27965 5.22625 3.77965\n-4.27965 5.22625 -2.77965\n"
      "2.27965 5.22625 -2.77965\nc 37708.496896 1.7277 0 0.07412 -0.753191 2.0659 0 0.07412\n",
      "long_cylinder.nff");
  expectEveryModeDrawsTheReference(scene);
}

// Found by the campaign: an 'up' of (-1e300, 1, 3.4e38), whose squared length overflows. Normalised as it
// was, it gave the camera a zero frame (every eye ray the same), which the paper's cells split otherwise
// than the reference traced. The frame is now that of the direction the file means.
TEST(HostileScenes, AHugeUpVectorStillFramesTheCamera) {
  const core::Scene scene = core::parseNff(
      "v\nfrom 0 0 -8\nat 0 0 0\nup -1e300 1 3.4e38\nangle 25\nhither 0.001\nresolution 8 8\n"
      "l -10 3 -20\nf 0.737 0.561 0.561 0.7 0.7 11.1434 0 1\n"
      "c 0 -0.649519 0.375 0.075 0 0.649519 -0.375 0.075\n",
      "huge_up.nff");
  core::Scene sane = scene;
  sane.camera.up = core::Vec3(-1, 0, 0);  // its direction, up to 1e-300
  EXPECT_TRUE(core::bitIdentical(renderReference(scene, sixteen(core::Precision::Double)).image,
                                 renderReference(sane, sixteen(core::Precision::Double)).image));
  expectEveryModeDrawsTheReference(scene);
}

// Class 3, ties: faces drawn twice, one over the other, in different colours (a polygon, a triangle patch, a
// sphere, and a square half under another). Every ray meets both at the same t; every intersector (brute
// force, BVHs, the paper's cells, the regions' BVHs) must take the one of smaller index, in both precisions.
TEST(HostileScenes, CoplanarDuplicatedFacesTakeTheFirstInEveryMode) {
  const core::Scene scene = core::parseNff(
      "v\nfrom 3 -6 4\nat 0 0 0\nup 0 0 1\nangle 45\nhither 0.01\nresolution 16 16\n"
      "l 2 -3 6\nl -4 -2 3\n"
      "f 1 0 0 0.6 0.3 20 0 0\np 4\n-3 -3 0\n3 -3 0\n3 3 0\n-3 3 0\n"
      "f 0 1 0 0.6 0.3 20 0 0\np 4\n-3 -3 0\n3 -3 0\n3 3 0\n-3 3 0\n"
      "f 0 0 1 0.6 0.3 20 0 0\np 4\n0 -3 0\n3 -3 0\n3 0 0\n0 0 0\n"
      "f 1 1 0 0.5 0.5 65 0 0\npp 3\n-2 -2 0.5 0 0 1\n2 -2 0.5 0 0 1\n0 2 0.5 0 0 1\n"
      "f 0 1 1 0.5 0.5 65 0 0\npp 3\n-2 -2 0.5 0 0 1\n2 -2 0.5 0 0 1\n0 2 0.5 0 0 1\n"
      "f 1 0 1 0.7 0.3 10 0 0\ns 0 0 1.5 0.75\nf 1 1 1 0.7 0.3 10 0 0\ns 0 0 1.5 0.75\n",
      "coplanar_duplicates.nff");
  // The tie rule's picture: the scene without the later copies (the green square, the blue half under the
  // red, the cyan patch, the white sphere) draws the same image. Their shadows are the same too: every copy
  // is opaque.
  core::Scene firstsOnly = scene;
  for (const std::size_t later : {6, 4, 2, 1})
    firstsOnly.objects.erase(firstsOnly.objects.begin() + std::ptrdiff_t(later));
  for (const core::Precision precision : {core::Precision::Float, core::Precision::Double})
    EXPECT_TRUE(core::bitIdentical(renderReference(scene, sixteen(precision)).image,
                                   renderReference(firstsOnly, sixteen(precision)).image))
        << core::nameOf(precision);
  expectEveryModeDrawsTheReference(scene);
}

// Class 3, garbage numbers: patches whose vertex normals are absurd (a component of 1.7e216, whose square
// overflows; one of 1e-300, whose square underflows; a denormal one), shaded with Ks 0.5 and a shine of 65,
// over a mirror so that their NaN-prone normals also reflect; a zero normal is refused by the reader. Every
// mode draws the same image.
TEST(HostileScenes, PatchesWithAbsurdNormalsAreShadedAlikeInEveryMode) {
  const core::Scene scene = core::parseNff(
      "v\nfrom 0 -6 3\nat 0 0 0\nup 0 0 1\nangle 50\nhither 0.01\nresolution 16 16\n"
      "l 1 -4 5\nl -3 -1 4\n"
      "f 0.5 0.5 0.5 0.2 0.8 5 0 0\np 4\n-4 -4 -1\n4 -4 -1\n4 4 -1\n-4 4 -1\n"
      "f 0.9 0.4 0.1 0.5 0.5 65 0 0\n"
      "pp 3\n-2 -1 0 0 1.7e216 1\n2 -1 0 1 0 1\n0 2 1 0 0 1\n"
      "pp 3\n-2 -1 0 1e-320 0 0\n0 2 1 1e-300 0 1e-300\n-3 2 0.5 -1.7e216 1.7e216 1.7e216\n"
      "pp 4\n1 0 -0.5 0 0 1e308\n3 0 -0.5 1e308 1e308 1e308\n3 2 0 0 0 -1\n1 2 0 0 1.7e216 0\n",
      "absurd_normals.nff");
  expectEveryModeDrawsTheReference(scene);
}

// Found by the campaign: a sphere of radius 3.4e38 in double around 0.15-size objects, whose tests from a
// point on it are noise (tests/fuzz/open/README.md). The light rays' shadow cache tested its last blocker
// without the boxes a BVH tests first, and so found hits the BVH culls: the paper's cells drew one of two
// images from run to run, depending on which blocker each processor had met last. The cache now answers
// only where the BVH behind it would meet the blocker, so every run draws the same image.
TEST(HostileScenes, TheShadowCacheLeavesNoTimingInTheImage) {
  const core::Scene scene = core::parseNff(
      "b -0 0.05 0.2\nv\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 25.006103515625\nhither 0.001\n"
      "resolution 256 256\nl -10 3 -20\nf 0.737 0.561 0.561 0.7 0.7 11.1434 0 1\n"
      "c -0.704769 -0.128258 -0.222149 0.075 0.704769 0.128258 0.222149 0.075\n"
      "c 0.256515 -0.352385 -0.610348 0.075 -0.256515 0.352385 0.610348 0.075\n"
      "s 0.704769 0.128258 0.222149 0.15\ns 0 0.649519 -0.375 0.15\ns -0.256515 0.352385 0.610348 3.4e38\n"
      "s -0.704769 -0.128258 -0.222149 0.15\ns 0.256515 -0.352385 -0.610348 0.15\n",
      "timing.nff");
  RenderSettings settings = sixteen(core::Precision::Double);
  settings.width = settings.height = 8;
  settings.shading.maxDepth = 3;
  MachineSettings paper = uniformGrid(2, 2, 512);
  paper.cells = node::CellStructure::Paper;
  paper.subsampleWindow = 2;
  MachineReport report;
  const core::Image first = renderMachineWatched(scene, settings, paper, report, "paper cells").image;
  for (int run = 1; run < 8; ++run)
    EXPECT_TRUE(
        core::bitIdentical(renderMachineWatched(scene, settings, paper, report, "paper cells").image, first))
        << "run " << run << " drew another image";
}

// The watchdog: a machine that loses its termination token never terminates; it must end with an error
// naming its processors and what each still holds, not sleep forever.
TEST(HostileScenes, AStalledMachineEndsWithAnErrorNamingItsProcessors) {
  const core::Scene scene = oneSphere("stall.nff");
  MachineSettings machine = uniformGrid(2, 2, 512);
  machine.loseTheTokenForTests = true;
  machine.stallPeriod = std::chrono::milliseconds(200);
  MachineReport report;
  const std::string message = runWatched(watchdogLimit(), "a stalled machine must end", [&]() -> std::string {
    try {
      renderMachine(scene, sixteen(core::Precision::Double), machine, &report);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  });
  EXPECT_NE(message.find("the machine stalled"), std::string::npos) << message;
  EXPECT_NE(message.find("processor 3 holds"), std::string::npos) << message;
}

// The threads' watchdog, for a processor inside one step all the period: its thread cannot be stopped nor
// joined, so the program ends, exit status 3, naming it.
TEST(HostileScenesDeathTest, AStuckProcessorOfTheThreadedMachineEndsTheProgramNamingIt) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const core::Scene scene = oneSphere("stuck.nff");
  MachineSettings machine = uniformGrid(2, 2, 512);
  machine.stallAStepForTests = true;
  machine.stallPeriod = std::chrono::milliseconds(300);
  EXPECT_EXIT(renderMachine(scene, sixteen(core::Precision::Double), machine), testing::ExitedWithCode(3),
              "the machine stalled.*processor 3 has been inside one step");
}

// The emulated machine's watchdog: a processor whose step never ends stops the simulated clock and every
// other actor with it; the wall-clock watch beside the maestro ends the simulation with an error naming it.
TEST(HostileScenes, AStuckProcessorOfTheEmulatedMachineIsNamed) {
  const core::Scene scene = oneSphere("stuck.nff");
  MachineSettings machine = uniformGrid(2, 2, 128);
  machine.emulate = builtinPlatform("ipsc1");
  machine.stallAStepForTests = true;
  machine.stallPeriod = std::chrono::milliseconds(300);
  MachineReport report;
  const std::string message = runWatched(watchdogLimit(), "a stuck emulated processor must end", [&] {
    try {
      renderMachine(scene, sixteen(core::Precision::Double), machine, &report);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  });
  EXPECT_NE(message.find("the machine stalled"), std::string::npos) << message;
  EXPECT_NE(message.find("processor 3 has been inside one step"), std::string::npos) << message;
}

}  // namespace
}  // namespace raycube::host
