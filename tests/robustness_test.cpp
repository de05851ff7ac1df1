// Adversarial scenes (issue 11): each class of input that once crashed, overflowed, hung or broke the
// bit-identity of the modes, held here by a test of its own. The fuzzer's reproducers replay separately
// (fuzz_regressions_test); these tests say what the user may rely on.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/image.h"
#include "core/nff_reader.h"
#include "core/precision.h"
#include "host/render/framebuffer.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"

namespace raycube::host {
namespace {

const char* kView = "v\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 30\nhither 0.001\nresolution 8 8\n";

RenderSettings tiny(core::Precision precision = core::Precision::Double) {
  RenderSettings s;
  s.width = s.height = 8;
  s.progress = false;
  s.precision = precision;
  return s;
}

MachineSettings smallMachine() {
  MachineSettings m;
  m.rows = m.columns = 2;
  return m;
}

void expectEveryModeMatchesReference(const core::Scene& scene, const RenderSettings& settings) {
  const core::Image reference = renderReference(scene, settings).image;
  EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, settings).image, reference)) << "image-parallel";
  EXPECT_TRUE(core::bitIdentical(renderMachine(scene, settings, smallMachine()).image, reference))
      << "machine";
}

// Class 1: each BVH split peels off one sphere; the tree would be 79 levels deep, past the traversal stack.
TEST(Robustness, DegenerateBvhDoesNotOverflowTheTraversalStack) {
  std::string text = std::string(kView) + "l 0 5 -10\nf 1 0.5 0.2 0.7 0.3 10 0 0\n";
  double z = 2;
  for (int i = 0; i < 80; ++i, z *= 17) text += "s 0 0 " + std::to_string(z) + " 1\n";
  const core::Scene scene = core::parseNff(text, "deep.nff");
  const RenderSettings settings = tiny();
  expectEveryModeMatchesReference(scene, settings);
  EXPECT_GT(renderReference(scene, settings).image.at(4, 4)[0], 0) << "the nearest sphere is lit";
}

// Class 2: two contributions that each saturate must not wrap the sample's sum to a negative value.
TEST(Robustness, SaturatedContributionsNeverWrap) {
  const core::Scene scene = core::parseNff(
      std::string(kView) + "l 3 4 -5\nf 1e10 1e10 1e10 1e10 0 0 0 0\ns 0 0 0 3\n", "bright.nff");
  const core::Image image = renderReference(scene, tiny()).image;
  EXPECT_GE(image.at(4, 4)[0], 2 * host::Framebuffer::kContributionLimit);
  expectEveryModeMatchesReference(scene, tiny());
}

// Saturation must not depend on arrival order: +max +max -max sums to +max whatever comes first.
TEST(Robustness, SaturatedSumsDoNotDependOnArrivalOrder) {
  const double big = 1e30, order[3][3] = {{big, big, -big}, {big, -big, big}, {-big, big, big}};
  core::Camera camera;
  camera.width = camera.height = 1;
  const core::View view(camera, 1, 1, core::Sampling::Centers);
  std::vector<core::Image> images;
  for (const auto& values : order) {
    host::Framebuffer frame(1, 1);
    for (double v : values) frame.add(core::Contribution{0, core::Color(v, -v, 0)});
    images.push_back(frame.resolve(view));
  }
  EXPECT_EQ(images[0].at(0, 0)[0], host::Framebuffer::kContributionLimit);
  EXPECT_EQ(images[0].at(0, 0)[1], -host::Framebuffer::kContributionLimit);
  for (const core::Image& image : images) EXPECT_TRUE(core::bitIdentical(image, images[0]));
}

// Class 3: a ray names its light in 16 bits; one more light than that is refused where it is written.
TEST(Robustness, TooManyLightsAreRefusedAtTheirLine) {
  std::string text = kView;
  for (std::size_t i = 0; i <= core::kMaxLights; ++i) text += "l 1 2 3\n";
  try {
    core::parseNff(text, "lights.nff");
    FAIL() << "expected a SceneError";
  } catch (const core::SceneError& e) {
    EXPECT_EQ(e.line(), 8 + int(core::kMaxLights));
    EXPECT_EQ(e.column(), 1);
    EXPECT_NE(std::string(e.what()).find("65536 lights"), std::string::npos) << e.what();
  }
  // A scene built in code is refused by every renderer.
  core::Scene scene = core::parseNff(std::string(kView) + "f 1 1 1 1 0 0 0 0\ns 0 0 0 1\n", "few.nff");
  scene.lights.resize(core::kMaxLights + 1);
  EXPECT_THROW(renderReference(scene, tiny()), std::invalid_argument);
  EXPECT_THROW(renderMachine(scene, tiny(), smallMachine()), std::invalid_argument);
}

// Class 4: overlapping polygons in the plane z = 0 (flat boxes at 0) tie exactly as in the reference, in
// both precisions, at the files' own resolution (16x16: the fuzz replay renders them at 8x8).
TEST(Robustness, CoplanarPolygonsAtZeroTieAsInTheReference) {
  for (const char* file : {"class4_coplanar_at_zero_a.nff", "class4_coplanar_at_zero_b.nff"}) {
    const core::Scene scene =
        core::readNff(std::filesystem::path(RAYCUBE_SOURCE_DIR) / "tests/fuzz/regressions" / file);
    for (const core::Precision precision : {core::Precision::Double, core::Precision::Float}) {
      SCOPED_TRACE(std::string(file) + " in " + core::nameOf(precision));
      RenderSettings settings = tiny(precision);
      settings.width = scene.camera.width;
      settings.height = scene.camera.height;
      expectEveryModeMatchesReference(scene, settings);
    }
  }
}

// Class 5: the eye inside a sphere of radius 6e7 around unit-size features: float hits on the small objects
// lie units off them (t ~ 6e7 has an ulp of 4), and the machine's cells must still hold them.
TEST(Robustness, FloatMachineAgreesInsideAHugeSphere) {
  const core::Scene scene = core::readNff(std::filesystem::path(RAYCUBE_SOURCE_DIR) /
                                          "tests/fuzz/regressions/class5_float_huge_sphere.nff");
  RenderSettings settings = tiny(core::Precision::Float);
  settings.width = settings.height = 16;
  const core::Image reference = renderReference(scene, settings).image;
  MachineSettings messages = smallMachine();
  messages.lightRays = node::LightRayMode::Messages;
  MachineSettings paper;
  paper.cells = node::CellStructure::Paper;
  // A reflected ray meets the small sphere and the floor at one float t: the regions' BVHs (the default)
  // must visit the sphere's box, entered as computed a few ulps beyond that t, as the paper's cells do.
  for (const MachineSettings& machine : {MachineSettings{}, messages, paper})
    EXPECT_TRUE(core::bitIdentical(renderMachine(scene, settings, machine).image, reference));
  EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, settings).image, reference));
  // Past float's bits, the scene is refused with advice rather than rendered differently by each mode.
  core::Scene wider = scene;
  std::get<core::Sphere>(wider.objects[0].shape).radius = 1e9;
  EXPECT_THROW(renderReference(wider, settings), std::invalid_argument);
}

// Class 6: an object so far away that rescaling would crush every other one to nothing is named, not drawn
// as a black image. Double holds the float case, and the error says so.
TEST(Robustness, AFarAwayObjectIsNamedInsteadOfErasingThePicture) {
  const std::string scene = std::string(kView) + "l 3 4 -5\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
  for (const auto& [far, precision, advice] :
       {std::tuple{"1e200", core::Precision::Double, "move or remove it"},
        std::tuple{"1e20", core::Precision::Float, "--precision double"}}) {
    const core::Scene s = core::parseNff(scene + "s " + far + " 0 0 1\n", "far.nff");
    try {
      renderImageParallel(s, tiny(precision));
      FAIL() << "expected std::invalid_argument for a sphere at " << far;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("far.nff:11"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(advice), std::string::npos) << e.what();
    }
  }
  // Within the range, the far sphere is kept and the near one still shows.
  const core::Scene held = core::parseNff(scene + "s 1e60 0 0 1\n", "far.nff");
  const core::Image image = renderReference(held, tiny()).image;
  EXPECT_GT(image.at(4, 4)[0], 0);
  expectEveryModeMatchesReference(held, tiny());
}

// Float's limit, exactly where the message puts it: a ratio (largest coordinate over smallest object) just
// below 2^29 renders the same in every mode; just above, it is refused, naming the far object and the small
// one, with the advice to render in double.
TEST(Robustness, TheFloatSpanLimitIsWhereTheMessageSaysAndNamesTheObjects) {
  const std::string scene = std::string(kView) + "l 3 4 -5\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
  const double limit = std::ldexp(1.0, core::kMaxSpanExponentOf<float> + 1);
  auto farSphere = [&](double span) {  // its centre + radius over the unit sphere's size, 2
    return core::parseNff(scene + fmt::format("s {:.17g} 0 0 1\n", 2 * span - 1), "span.nff");
  };
  const core::Scene under = farSphere(0.99 * limit);
  expectEveryModeMatchesReference(under, tiny(core::Precision::Float));
  try {
    renderReference(farSphere(1.01 * limit), tiny(core::Precision::Float));
    FAIL() << "expected std::invalid_argument past float's span";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    for (const char* words : {"span.nff:11: the sphere 's'", "span.nff:10: the sphere 's'",
                              "float arithmetic", "below 2^29", "--precision double"})
      EXPECT_NE(message.find(words), std::string::npos) << words << " in: " << message;
  }
}

// Class 7: only a regular file has an end: a device or a FIFO is refused by name, at once.
TEST(Robustness, ScenesThatAreNotRegularFilesAreRefused) {
  try {
    core::readNff("/dev/zero");
    FAIL() << "expected a SceneError";
  } catch (const core::SceneError& e) {
    EXPECT_NE(
        std::string(e.what()).find("/dev/zero: expected a regular scene file, found a character device"),
        std::string::npos)
        << e.what();
  }
  const std::filesystem::path fifo =
      std::filesystem::temp_directory_path() / ("raycube_fifo_" + std::to_string(::getpid()) + ".nff");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(core::readNff(fifo), core::SceneError);  // would block forever in open()
  std::filesystem::remove(fifo);
}

}  // namespace
}  // namespace raycube::host
