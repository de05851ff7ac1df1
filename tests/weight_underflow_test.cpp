// Issue 6, "Weights underflow": between two facing mirrors a depth-64 tree carries coeff = ks^(level - 1),
// which for small ks runs through denormals down to 0. Whatever the weights do, the tree must stay
// complete, the picture finite, and the two sequential renderers bit-identical.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spd/facing_mirrors.h"
#include "host/render/framebuffer.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"

namespace raycube::host {
namespace {

constexpr int kSide = 16;
constexpr int kDepth = core::kFacingMirrorsMinBounces;
constexpr std::uint64_t kEyeRays = std::uint64_t(kSide) * kSide;

RenderSettings mirrorSettings(int maxDepth, core::Precision precision = core::Precision::Double) {
  RenderSettings settings;
  settings.precision = precision;
  settings.width = kSide;
  settings.height = kSide;
  settings.sampling = core::Sampling::Centers;
  settings.shading.maxDepth = maxDepth;
  settings.shading.minWeight = 0;  // the SPD rule: every reflected ray is spawned, however small its coeff
  settings.threads = 2;
  settings.progress = false;
  return settings;
}

core::Image referenceImage(double ks, int maxDepth) {
  return renderReference(core::makeFacingMirrors(ks), mirrorSettings(maxDepth)).image;
}

std::size_t nonFiniteChannels(const core::Image& image) {
  std::size_t count = 0;
  for (const core::Color& c : image.pixels)
    for (int ch = 0; ch < 3; ++ch) count += std::isfinite(c[ch]) ? 0 : 1;
  return count;
}

TEST(FacingMirrors, RejectsReflectanceOutsideZeroToOne) {
  EXPECT_THROW(core::makeFacingMirrors(-0.01), std::invalid_argument);
  EXPECT_THROW(core::makeFacingMirrors(1.01), std::invalid_argument);
  EXPECT_THROW(core::makeFacingMirrors(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  const core::Scene scene = core::makeFacingMirrors(0);
  EXPECT_EQ(scene.name, "facing_mirrors");
  EXPECT_EQ(core::makeFacingMirrors(1).materials.at(0).ks, 1.0);
}

struct UnderflowCase {
  const char* name;
  double ks;
  // Light rays per eye ray: one per hit (the light is in front of every hit) while coeff * I * bracket is
  // not 0. With ks = 1e-160 level 3 carries 1e-320 (denormal), level 4 carries 0: three.
  std::uint64_t lightRaysPerEyeRay;
};

void PrintTo(const UnderflowCase& c, std::ostream* os) {
  *os << c.name;
}

class WeightUnderflow : public testing::TestWithParam<UnderflowCase> {};

TEST_P(WeightUnderflow, DepthSixtyFourTreeIsCompleteFiniteAndIdenticalInBothRenderers) {
  const core::Scene scene = core::makeFacingMirrors(GetParam().ks);
  const RenderResult reference = renderReference(scene, mirrorSettings(kDepth));
  const RenderResult parallel = renderImageParallel(scene, mirrorSettings(kDepth));
  for (const RenderResult* result : {&reference, &parallel}) {
    SCOPED_TRACE(result->mode);
    const core::TraceCounters& c = result->counters;
    EXPECT_EQ(c.nonFinite, 0u);
    EXPECT_EQ(nonFiniteChannels(result->image), 0u);
    EXPECT_EQ(c.of(core::RayKind::Eye), kEyeRays);
    // Levels 2..64 of every tree: each of the 63 rays before them hit a mirror, whatever its coeff.
    EXPECT_EQ(c.of(core::RayKind::Reflected), kEyeRays * (kDepth - 1));
    EXPECT_EQ(c.of(core::RayKind::Refracted), 0u);
    EXPECT_EQ(c.of(core::RayKind::Light), kEyeRays * GetParam().lightRaysPerEyeRay);
  }
  EXPECT_TRUE(core::bitIdentical(reference.image, parallel.image));
}

INSTANTIATE_TEST_SUITE_P(Reflectances, WeightUnderflow,
                         testing::Values(UnderflowCase{"ks_1", 1, kDepth},
                                         UnderflowCase{"ks_0_999", 0.999, kDepth},
                                         UnderflowCase{"ks_0_5", 0.5, kDepth},
                                         UnderflowCase{"ks_1e_5", 1e-5, kDepth},
                                         UnderflowCase{"ks_1e_160", 1e-160, 3}),
                         [](const testing::TestParamInfo<UnderflowCase>& info) { return info.param.name; });

// In float the weights reach denormals (below 1.2e-38) after far fewer bounces: ks = 0.25 at level 64,
// 0.2 from level 56, 1e-5 from level 9. The trees stay complete, the pictures finite, and the reference,
// the image-parallel renderer and the machine agree bit for bit.
class FloatWeightUnderflow : public testing::TestWithParam<double> {};

TEST_P(FloatWeightUnderflow, DepthSixtyFourTreeIsCompleteFiniteAndIdenticalEverywhere) {
  const core::Scene scene = core::makeFacingMirrors(GetParam());
  const RenderSettings settings = mirrorSettings(kDepth, core::Precision::Float);
  const RenderResult reference = renderReference(scene, settings);
  const RenderResult parallel = renderImageParallel(scene, settings);
  MachineSettings machine;
  machine.rows = machine.columns = 2;
  machine.queueCapacity = 4;
  const RenderResult emulated = renderMachine(scene, settings, machine);
  for (const RenderResult* result : {&reference, &parallel, &emulated}) {
    SCOPED_TRACE(result->mode);
    EXPECT_EQ(result->precision, core::Precision::Float);
    EXPECT_EQ(result->counters.nonFinite, 0u);
    EXPECT_EQ(nonFiniteChannels(result->image), 0u);
    EXPECT_EQ(result->counters.of(core::RayKind::Reflected), kEyeRays * (kDepth - 1));
    EXPECT_TRUE(core::bitIdentical(result->image, reference.image));
  }
}

INSTANTIATE_TEST_SUITE_P(Reflectances, FloatWeightUnderflow, testing::Values(1.0, 0.999, 0.25, 0.2, 1e-5),
                         [](const testing::TestParamInfo<double>& info) {
                           return "case_" + std::to_string(info.index);
                         });

// Every contribution is a product of non-negative factors, each non-decreasing in ks, over a geometry that
// does not depend on ks; float and fixed-point rounding are monotone. So no pixel may darken as ks grows.
TEST(UnderflowedWeights, BrighterMirrorsNeverDarkenAPixel) {
  const std::vector<double> increasing{0, 1e-160, 1e-5, 0.5, 0.999, 1};
  std::vector<core::Image> images;
  for (double ks : increasing) images.push_back(referenceImage(ks, kDepth));
  for (std::size_t i = 0; i + 1 < images.size(); ++i) {
    std::size_t darker = 0;
    double sumBelow = 0, sumAbove = 0;
    for (std::size_t p = 0; p < images[i].pixels.size(); ++p) {
      for (int ch = 0; ch < 3; ++ch) {
        darker += images[i + 1].pixels[p][ch] < images[i].pixels[p][ch] ? 1 : 0;
        sumBelow += images[i].pixels[p][ch];
        sumAbove += images[i + 1].pixels[p][ch];
      }
    }
    EXPECT_EQ(darker, 0u) << "ks " << increasing[i] << " -> " << increasing[i + 1];
    // From 1e-5 up, a larger ks visibly adds light (at least the level-2 ambient term).
    if (increasing[i] >= 1e-5) {
      EXPECT_LT(sumBelow, sumAbove) << "ks " << increasing[i];
    }
  }
}

// With ks = 1 no energy leaves the tree: each of the 64 levels adds at least its ambient term
// coeff * A * Kd = 1 * 1/2 * 0.1 (A = sqrt(L) / 2L for one light), rounded once to the frame buffer step.
TEST(UnderflowedWeights, LosslessMirrorsAddTheAmbientTermOfEveryLevel) {
  const double ambientPerLevel = 0.5 * 0.1 - 0.5 / host::Framebuffer::kFixedScale;
  const core::Image image = referenceImage(1, kDepth);
  for (const core::Color& c : image.pixels)
    for (int ch = 0; ch < 3; ++ch) ASSERT_GE(c[ch], kDepth * ambientPerLevel);
}

// Contributions below half the frame buffer's 2^-40 step round to 0: bounces whose weight has underflowed
// must leave the picture bit for bit as if the tree had stopped before them.
TEST(UnderflowedWeights, UnderflowedBouncesAddNothing) {
  // Level 2 carries 1e-160, level 3 a denormal, the rest 0: the picture of a mirror that does not reflect.
  EXPECT_TRUE(core::bitIdentical(referenceImage(1e-160, kDepth), referenceImage(0, kDepth)));
  // Beyond level 8 coeff is at most 1e-35; levels 63 and 64 carry denormals.
  const core::Image deep = referenceImage(1e-5, kDepth);
  EXPECT_TRUE(core::bitIdentical(deep, referenceImage(1e-5, 8)));
  EXPECT_FALSE(core::bitIdentical(deep, referenceImage(1e-5, 1)));  // level 2 does show: the check can see
}

}  // namespace
}  // namespace raycube::host
