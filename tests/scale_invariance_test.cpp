// A scene's picture does not depend on its units. Every tolerance of the renderer is relative
// (core/tolerances.h: spawn offsets, box padding), so the same scene in micrometres or in kilometres must
// render the same image; an absolute epsilon anywhere shows up here as acne at large scales or as light
// leaking through at small ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "core/image.h"
#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

// Near the point where the big ball of the sphereflake rests on the floor, (0, 0, -0.5): two surfaces
// meeting at a grazing angle, lit floor in front, the shadowed wedge between floor and ball, and the ball's
// underside reflecting the floor. The hardest place for spawn offsets.
core::Scene contactNeighbourhood() {
  core::Scene scene = core::makeBalls(2);
  scene.name = "balls2-contact";
  scene.camera.from = core::Vec3(0.3, 0.3, -0.45);
  scene.camera.at = core::Vec3(0, 0, -0.5);
  scene.camera.hither = 0.001;
  return scene;
}

core::Scene sceneByName(const std::string& name) {
  if (name == "balls2") return core::makeBalls(2);
  if (name == "contact") return contactNeighbourhood();
  return core::readNff(testing_support::scenePath(name + ".nff"));
}

RenderResult render(const core::Scene& scene, int side) {
  return renderImageParallel(scene, settingsFor(side));
}

// The pixels that differ most, for a failure message a reader can act on.
std::string worstPixels(const core::Image& a, const core::Image& b, int count) {
  struct Diff {
    int x, y;
    double d;
  };
  std::vector<Diff> diffs;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const core::Color d = glm::abs(a.at(x, y) - b.at(x, y));
      diffs.push_back({x, y, std::max({d.x, d.y, d.z})});
    }
  std::sort(diffs.begin(), diffs.end(), [](const Diff& p, const Diff& q) { return p.d > q.d; });
  std::ostringstream text;
  for (int i = 0; i < count && i < int(diffs.size()) && diffs[i].d > core::kOneSrgbLevel; ++i) {
    const core::Color& pa = a.at(diffs[i].x, diffs[i].y);
    const core::Color& pb = b.at(diffs[i].x, diffs[i].y);
    text << "\n  (" << diffs[i].x << ", " << diffs[i].y << "): " << pa.x << " " << pa.y << " " << pa.z
         << " vs " << pb.x << " " << pb.y << " " << pb.z;
  }
  return text.str();
}

struct ScaleCase {
  std::string scene;
  double factor;
};

void PrintTo(const ScaleCase& c, std::ostream* os) {
  *os << c.scene << " times " << c.factor;
}

class ScaleInvariance : public testing::TestWithParam<ScaleCase> {};

TEST_P(ScaleInvariance, SameImageAsAtUnitScale) {
  const int side = sanitized() ? 32 : 64;
  const core::Scene base = sceneByName(GetParam().scene);
  const RenderResult unit = render(base, side);
  const RenderResult other = render(core::scaledBy(base, GetParam().factor), side);
  EXPECT_EQ(firstNonFinitePixel(other.image), -1);
  EXPECT_EQ(other.counters.nonFinite, 0u);
  const core::ImageDifference diff = core::compareImages(unit.image, other.image);
  RecordProperty("max_abs_difference", testing::PrintToString(diff.maxAbs));
  RecordProperty("pixels_over_one_level", std::to_string(diff.pixelsOver));
  EXPECT_LE(diff.maxAbs, core::kOneSrgbLevel)
      << diff.pixelsOver << " pixels differ by more than one sRGB level; worst (unit scale vs scaled):"
      << worstPixels(unit.image, other.image, 10);
  // Which object each ray meets is scale-free too, so the ray tree has the same shape.
  for (int k = 0; k < core::kRayKinds; ++k)
    EXPECT_EQ(unit.counters.rays[k], other.counters.rays[k])
        << core::rayKindName(core::RayKind(k)) << " rays";
}

std::vector<ScaleCase> scaleCases() {
  std::vector<ScaleCase> cases;
  for (const char* scene : {"balls2", "contact", "gears1"})
    for (double factor : {1e-4, 1e4, 1e6}) cases.push_back({scene, factor});
  return cases;
}

std::string scaleCaseName(const testing::TestParamInfo<ScaleCase>& info) {
  std::ostringstream name;
  name << info.param.scene << "_times_1e" << std::lround(std::log10(info.param.factor));
  std::string s = name.str();
  std::replace(s.begin(), s.end(), '-', 'm');
  return s;
}

INSTANTIATE_TEST_SUITE_P(Scenes, ScaleInvariance, testing::ValuesIn(scaleCases()), scaleCaseName);

// The reference (brute force) and the BVH still agree bit for bit far from unit scale: box padding is
// relative, so the BVH never culls what brute force finds.
TEST(ScaleInvariance, ReferenceAndBvhAgreeAtLargeAndSmallScale) {
  const int side = sanitized() ? 24 : 48;
  RenderSettings settings;
  settings.width = side;
  settings.height = side;
  settings.progress = false;
  for (double factor : {1e-4, 1e6}) {
    const core::Scene scene = core::scaledBy(core::makeBalls(2), factor);
    EXPECT_TRUE(core::bitIdentical(renderReference(scene, settings).image,
                                   renderImageParallel(scene, settings).image))
        << "scale " << factor;
  }
}

// ---- Acne at the contact point --------------------------------------------------------------------------
// Self-intersection acne (a spawned ray meeting the surface it leaves) makes a light ray find its own
// surface: the pixel loses that light's term and turns dark among lit neighbours; a reflected ray that
// meets its own surface shades the inside of the ball. Either way it is high-frequency noise: single pixels
// that disagree with a flat neighbourhood. True image features here (shadow boundaries, the silhouette of
// the ball, the thin shadowed wedge) are edges and lines, where the neighbours themselves disagree.
// So a pixel is a speckle when its luminance is more than kSpeckleContrast away from the median of its 8
// neighbours while those neighbours span less than kSpeckleContrast. The light a light ray carries here is
// ~0.08 (lit floor 0.27 vs 0.18 in shadow), well above the threshold; smooth shading varies by ~0.005 per
// pixel, well below it. Dense acne (most pixels of a surface) is not isolated; the scale test above catches
// it as a difference from the unit-scale image instead.
constexpr double kSpeckleContrast = 0.03;

double luminance(const core::Color& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

struct Speckle {
  int x, y;
  double value, median;
};

std::vector<Speckle> findSpeckles(const core::Image& image) {
  std::vector<Speckle> found;
  for (int y = 1; y + 1 < image.height; ++y) {
    for (int x = 1; x + 1 < image.width; ++x) {
      std::vector<double> around;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx != 0 || dy != 0) around.push_back(luminance(image.at(x + dx, y + dy)));
      std::sort(around.begin(), around.end());
      const double median = 0.5 * (around[3] + around[4]);
      const double value = luminance(image.at(x, y));
      if (around.back() - around.front() < kSpeckleContrast && std::abs(value - median) > kSpeckleContrast)
        found.push_back({x, y, value, median});
    }
  }
  return found;
}

std::string describe(const std::vector<Speckle>& speckles) {
  std::ostringstream text;
  for (std::size_t i = 0; i < speckles.size() && i < 10; ++i)
    text << "\n  (" << speckles[i].x << ", " << speckles[i].y << "): luminance " << speckles[i].value
         << ", neighbours' median " << speckles[i].median;
  return text.str();
}

class ContactPoint : public testing::TestWithParam<double> {};

TEST_P(ContactPoint, ShadesWithoutSpeckles) {
  const RenderResult result = render(core::scaledBy(contactNeighbourhood(), GetParam()), 64);
  ASSERT_EQ(firstNonFinitePixel(result.image), -1);
  const std::vector<Speckle> speckles = findSpeckles(result.image);
  EXPECT_TRUE(speckles.empty()) << speckles.size() << " isolated pixels:" << describe(speckles);
}

INSTANTIATE_TEST_SUITE_P(Scales, ContactPoint, testing::Values(1e-4, 1.0, 1e4, 1e6),
                         [](const testing::TestParamInfo<double>& info) {
                           const long e = std::lround(std::log10(info.param));
                           return "times_1e" + (e < 0 ? "m" + std::to_string(-e) : std::to_string(e));
                         });

// The detector has teeth: the same render with acne-like pixels (one light's term removed from a few
// scattered lit pixels) is caught, pixel for pixel.
TEST(ContactPoint, DetectorFindsInjectedAcne) {
  core::Image image = render(contactNeighbourhood(), 64).image;
  ASSERT_TRUE(findSpeckles(image).empty());
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(2, 61);
  std::vector<std::pair<int, int>> where;
  for (int attempt = 0; attempt < 100000 && where.size() < 20; ++attempt) {
    const int x = coordinate(random), y = coordinate(random);
    // Only where the neighbourhood is flat and no earlier injection is close, as acne on a lit surface.
    bool clear = true;
    for (const auto& [px, py] : where) clear = clear && (std::abs(px - x) > 2 || std::abs(py - y) > 2);
    double lo = 1e9, hi = -1e9;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const double l = luminance(image.at(x + dx, y + dy));
        lo = std::min(lo, l);
        hi = std::max(hi, l);
      }
    if (!clear || hi - lo > 0.005 || luminance(image.at(x, y)) < 0.2) continue;
    image.at(x, y) -= core::Color(0.8 * 0.289) * core::Color(1, 0.75, 0.33) * 0.4;  // Kd C I (N.L)
    where.emplace_back(x, y);
  }
  ASSERT_GE(where.size(), 10u) << "too few flat lit pixels to test the detector on";
  EXPECT_EQ(findSpeckles(image).size(), where.size());
}

}  // namespace
}  // namespace raycube::host
