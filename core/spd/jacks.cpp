// SPD jacks.c (Alexander Enzmann): a jack (three cylinders, six spheres at their ends) with a half-size
// jack in each of its eight octants, recursively, like a Menger sponge. One light. jacks.c places each jack
// through the SPD's transformation stack; the NFF output carries the transformed spheres and cylinders.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/spd/generators.h"
#include "core/spd/matrix.h"
#include "core/spd/output.h"

namespace raycube::core {

namespace {

constexpr double kArmRadius = 0.1;
constexpr double kKnobRadius = 0.2;

// jacks.c make_jack_obj(): one jack, shrunk to 0.75 so neighbours do not overlap, placed by `place`.
void outputJack(SpdOutput& out, const SpdMatrix& place) {
  const SpdMatrix tx = spdProduct(spdScaling(Vec3(0.75, 0.75, 0.75)), place);
  const double scale = std::fabs(spdScaleOf(tx));
  // Written out rather than negated: -Vec3(1, 0, 0) has negative zeros, which can print as "-0".
  const Vec3 ends[6] = {Vec3(1, 0, 0),  Vec3(0, 1, 0),  Vec3(0, 0, 1),
                        Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)};
  for (int axis = 0; axis < 3; ++axis) {
    out.cylcone(spdTransformPoint(ends[axis + 3], tx), kArmRadius * scale, spdTransformPoint(ends[axis], tx),
                kArmRadius * scale);
  }
  for (const Vec3& end : ends) out.sphere(spdTransformPoint(end, tx), kKnobRadius * scale);
}

// jacks.c make_rec_jack(): the jack, then a half-size one centred in each octant, x outermost.
void makeRecJack(SpdOutput& out, const SpdMatrix& place, int depth, int maxDepth) {
  outputJack(out, place);
  if (depth >= maxDepth) return;
  for (double i = -0.5; i <= 0.5; i += 1) {
    for (double j = -0.5; j <= 0.5; j += 1) {
      for (double k = -0.5; k <= 0.5; k += 1) {
        const SpdMatrix moved = spdProduct(spdTranslation(Vec3(i, j, k)), place);
        makeRecJack(out, spdProduct(spdScaling(Vec3(0.5, 0.5, 0.5)), moved), depth + 1, maxDepth);
      }
    }
  }
}

}  // namespace

Scene makeJacks(int size) {
  requireSpdSize("jacks", size, kMaxJacksSize, "the recursion depth: 1 gives 9 primitives, 4 gives 5265");
  SpdOutput out(fmt::format("jacks{}", size));
  out.background(Color(0.2, 0.05, 0.2));  // dark purple
  out.viewpoint(Vec3(0, 0, -8), Vec3(0, 0, 0), Vec3(0, 1, 0), 25.0, 0.001, 256, 256);
  out.light(Vec3(-10, 3, -20));

  // The whole group turned -30 degrees about x, then -20 about y (the SPD stack applies the last pushed
  // transformation first, so the product reads from the object outwards).
  const SpdMatrix tiltedX =
      spdProduct(spdRotation(SpdAxis::X, -30 * std::numbers::pi / 180.0), spdIdentity());
  const SpdMatrix turned = spdProduct(spdRotation(SpdAxis::Y, -20 * std::numbers::pi / 180.0), tiltedX);
  out.color(Color(0.737, 0.561, 0.561), 0.7, 0.7, 20.0, 0.0, 1.0);  // pink
  std::size_t jacks = 0;
  for (int level = 0, count = 1; level < size; ++level, count *= 8) jacks += count;
  out.reserve(9 * jacks);
  makeRecJack(out, turned, 1, size);
  return std::move(out).finish();
}

}  // namespace raycube::core
