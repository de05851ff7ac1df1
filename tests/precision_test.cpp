// --precision float|double (issue 6): one tracer, two arithmetics. Float rays give another picture than
// double ones, differing at silhouettes and shadow edges only, and the same picture in every renderer; a
// float ray message is smaller; and float degrades gracefully where its range ends.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "core/image.h"
#include "core/intersect.h"
#include "core/spd/balls.h"
#include "core/tolerances.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

RenderSettings inPrecision(RenderSettings settings, core::Precision precision) {
  settings.precision = precision;
  return settings;
}

double fractionOver(const core::ImageDifference& d, const core::Image& image) {
  return double(d.pixelsOver) / double(image.pixels.size());
}

// Float moves a hit by a few float ulps: only pixels whose rays pass within that of a silhouette or a
// shadow boundary change, so the picture agrees with double's except at a small fraction of its pixels.
TEST(Precision, FloatDiffersFromDoubleOnlyAtEdges) {
  const int side = sanitized() ? 48 : 128;
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = settingsFor(side);
  const RenderResult doubles = renderReference(scene, settings);
  const RenderResult floats = renderReference(scene, inPrecision(settings, core::Precision::Float));
  EXPECT_EQ(doubles.precision, core::Precision::Double);
  EXPECT_EQ(floats.precision, core::Precision::Float);
  EXPECT_FALSE(core::bitIdentical(doubles.image, floats.image)) << "float must actually be used";
  const core::ImageDifference d = core::compareImages(doubles.image, floats.image);
  EXPECT_GE(d.psnr, 40.0);
  EXPECT_LE(fractionOver(d, floats.image), 0.02) << d.pixelsOver << " pixels over one sRGB level";
  // The same trees: a handful of rays at edges go elsewhere, none is lost.
  const double rays = double(doubles.counters.totalRays());
  EXPECT_NEAR(double(floats.counters.totalRays()), rays, 0.01 * rays);
  EXPECT_EQ(floats.counters.nonFinite, 0u);
}

// Ray state in float: origin, direction, t range, weight and coeff take half the bytes.
TEST(Precision, FloatRayMessagesAreSmaller) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings machine;
  machine.rows = machine.columns = 2;
  std::size_t bytes[2] = {};
  for (core::Precision p : {core::Precision::Float, core::Precision::Double}) {
    MachineReport report;
    renderMachineWatched(scene, inPrecision(settingsFor(16), p), machine, report, core::nameOf(p));
    bytes[int(p)] = report.messageBytes;
  }
  EXPECT_EQ(bytes[int(core::Precision::Double)], 128u);
  EXPECT_EQ(bytes[int(core::Precision::Float)], 80u);
}

// The BSP partitions with light pyramids and the tightest FIFOs, in float: the reference's picture.
TEST(Precision, FloatMachineOnBspPartitionsMatchesTheFloatReference) {
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = inPrecision(settingsFor(sanitized() ? 24 : 48), core::Precision::Float);
  const RenderResult reference = renderReference(scene, settings);
  for (int processors : {5, 16}) {
    for (std::size_t capacity : {std::size_t(1), std::size_t(128)}) {
      MachineSettings machine;
      machine.rows = 1;
      machine.columns = processors;
      machine.balance = Balance::Bsp;
      machine.subsampleWindow = 4;
      machine.queueCapacity = capacity;
      renderAndCompare(scene, reference, settings, machine,
                       "float BSP " + std::to_string(processors) + " capacity " + std::to_string(capacity));
    }
  }
}

// A thin cylinder (a jacks rod: radius 0.019, 0.37 long) seen from 20 to 50 units away: a float hit lies on
// its surface, within the box a BVH culls by, where solving from the ray's far origin once reported hits 6%
// of the radius outside the box (so a BVH and a test of every object disagreed).
TEST(Precision, FloatHitsOnAThinCylinderSeenFromAfarLieOnIt) {
  const core::Cone rod{core::Vec3(0.49, -0.26, -0.57), 0.019, core::Vec3(0.49, 0.07, -0.76), 0.019};
  core::Object object;
  object.shape = rod;
  const core::Box box = core::boundsOf(object, core::kFloatBoxPaddingRelative);
  const core::Vec3 axis = glm::normalize(rod.apex - rod.base);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1, 1), along(0, 1), distance(20, 50);
  int hits = 0;
  for (int n = 0; n < 20000; ++n) {
    const core::Vec3 target = rod.base + along(random) * (rod.apex - rod.base) +
                              0.03 * core::Vec3(unit(random), unit(random), unit(random));
    const core::Vec3 away = glm::normalize(core::Vec3(unit(random), unit(random), unit(random)));
    const core::BasicRay<float> ray{core::Vec3Of<float>(target + distance(random) * away),
                                    core::Vec3Of<float>(-away), 0, std::numeric_limits<float>::infinity()};
    const float t = core::nearestHit(object, ray, ray.tMax);
    if (t == std::numeric_limits<float>::infinity()) continue;
    ++hits;
    const core::Vec3 point(ray.at(t));
    ASSERT_TRUE(glm::all(glm::greaterThanEqual(point, box.lo)) && glm::all(glm::lessThanEqual(point, box.hi)))
        << "ray " << n;
    const core::Vec3 fromBase = point - rod.base;
    const double offAxis = glm::length(fromBase - glm::dot(fromBase, axis) * axis);
    // Off the surface by no more than the rounding of origin + t * direction.
    EXPECT_NEAR(offAxis, rod.baseRadius, 4 * std::numeric_limits<float>::epsilon() * (1 + double(t)))
        << "ray " << n;
  }
  EXPECT_GT(hits, 2000);
}

// ---- The extremes of scale -------------------------------------------------------------------------

struct ScaleRow {
  int exponent;
  double fractionOver = 0, maxAbs = 0;
  std::size_t nonFinite = 0;
};

const std::vector<int> kScaleExponents{-300, -200, -100, -30, -24, -21, -18, -15, -12, -9,  -6,  -3, 0,
                                       3,    6,    9,    12,  15,  18,  21,  24,  30,  100, 200, 300};

// balls2 scaled by 10^k, in `precision`, against the double picture at scale 1.
std::vector<ScaleRow> scaleStudy(core::Precision precision, int side) {
  const core::Scene base = core::makeBalls(2);
  const RenderSettings settings = settingsFor(side);
  const core::Image unit = renderReference(base, settings).image;
  std::vector<ScaleRow> rows;
  for (int k : kScaleExponents) {
    const RenderResult r =
        renderReference(core::scaledBy(base, std::pow(10.0, k)), inPrecision(settings, precision));
    const core::ImageDifference d = core::compareImages(unit, r.image);
    rows.push_back(
        ScaleRow{k, fractionOver(d, r.image), d.maxAbs, nonFinitePixels(r.image) + r.counters.nonFinite});
  }
  return rows;
}

// Without rescaling, float broke from 1e9 (the floor's normal, a cross product squared, overflowed to a zero
// normal: no light on the floor) and from 1e-15 (it underflowed: NaN normals). Rescaled by a power of two,
// float gives its scale-1 picture over double's whole range, as double does.
TEST(PrecisionScale, FloatAndDoubleKeepThePictureFrom1em300To1e300) {
  const int side = sanitized() ? 16 : 48;
  const std::vector<ScaleRow> floats = scaleStudy(core::Precision::Float, side);
  const std::vector<ScaleRow> doubles = scaleStudy(core::Precision::Double, side);
  std::printf("  scale    float: pixels over 1/255, max   double: max (each against double at scale 1)\n");
  for (std::size_t i = 0; i < floats.size(); ++i) {
    const ScaleRow &f = floats[i], &d = doubles[i];
    std::printf("  1e%+04d  %6.2f%%  %.3f              %.1e\n", f.exponent, 100 * f.fractionOver, f.maxAbs,
                d.maxAbs);
    EXPECT_EQ(f.nonFinite + d.nonFinite, 0u) << "scale 1e" << f.exponent;
    EXPECT_LE(f.fractionOver, 0.03) << "float at scale 1e" << f.exponent;
    EXPECT_LE(d.maxAbs, core::kOneSrgbLevel) << "double at scale 1e" << d.exponent;
  }
}

// What the rescaling repairs: a polygon's normal in float arithmetic at 1e10.
TEST(PrecisionScale, RescalingKeepsFloatNormalsUnitLength) {
  core::Scene scene = core::makeBalls(1);
  const core::Scene far = core::scaledBy(scene, 1e10);
  const core::Object& floor = far.objects.at(0);
  ASSERT_TRUE(std::holds_alternative<core::Polygon>(floor.shape));
  core::BasicRay<float> down{
      {0.1e10f, 0.1e10f, 1e10f}, {0, 0, -1}, 0, std::numeric_limits<float>::infinity()};
  const float t = core::nearestHit(floor, down, std::numeric_limits<float>::infinity());
  ASSERT_LT(t, std::numeric_limits<float>::infinity());
  EXPECT_NE(glm::length(core::surfaceAt(floor, down, t).geometricNormal), 1.0f) << "the defect is visible";
  const std::optional<core::Scene> rescaled = core::rescaledFor(far, core::Precision::Float);
  ASSERT_TRUE(rescaled.has_value());
  EXPECT_FALSE(core::rescaledFor(scene, core::Precision::Float).has_value()) << "scale 1 is left alone";
  EXPECT_FALSE(core::rescaledFor(far, core::Precision::Double).has_value()) << "double needs no rescaling";
  const double factor = rescaled->camera.from.x / far.camera.from.x;
  EXPECT_EQ(factor, std::exp2(std::round(std::log2(factor)))) << "a power of two: exact";
  const core::BasicRay<float> near{down.origin * float(factor), down.direction, 0, down.tMax};
  const core::Object& rescaledFloor = rescaled->objects.at(0);
  const float tNear = core::nearestHit(rescaledFloor, near, std::numeric_limits<float>::infinity());
  EXPECT_NEAR(glm::length(core::surfaceAt(rescaledFloor, near, tNear).geometricNormal), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace raycube::host
