#include "core/view.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

#include "core/tolerances.h"

namespace raycube::core {

namespace {

// v itself, unless its squared length overflows or underflows (an 'up' of 1e300): then v scaled by its
// largest component. Normalised as it was, such a vector gave a zero frame, every eye ray the same, and the
// machine's regions nothing to split (issue 41). Every other camera's frame is computed exactly as ever.
Vec3 tamed(const Vec3& v) {
  const double squared = glm::dot(v, v);
  if (std::isfinite(squared) && squared > 0x1p-900) return v;
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest > 0 && std::isfinite(largest) ? v / largest : v;
}
Vec3 directionOf(const Vec3& v) {
  return glm::normalize(tamed(v));
}

}  // namespace

View::View(const Camera& camera, int width, int height, Sampling sampling, int raysPerSample)
    : width_(width),
      height_(height),
      sampling_(sampling),
      eye_(camera.from),
      hither_(camera.hither),
      raysPerSample_(raysPerSample) {
  if (width < 1 || height < 1) throw std::invalid_argument("image size must be at least 1x1");
  if (raysPerSample < 1) throw std::invalid_argument("samples per pixel must be at least 1");
  const bool corners = sampling == Sampling::Corners;
  samplesX_ = width + (corners ? 1 : 0);
  samplesY_ = height + (corners ? 1 : 0);
  offsetPixels_ = corners ? 0.5 : 0.0;
  forward_ = directionOf(camera.at - camera.from);
  right_ = directionOf(glm::cross(forward_, tamed(camera.up)));
  up_ = glm::cross(right_, forward_);
  // NFF: angle spans the centres of the outer pixel rows/columns; pixels are square (aspect 1).
  const double span = 2 * std::tan(camera.angleDegrees * std::numbers::pi / 360.0);
  pitch_ = span / std::max(1, std::max(width, height) - 1);
}

double View::sampleU(int sx) const {
  return (sx - offsetPixels_ - 0.5 * (width_ - 1)) * pitch_;
}
double View::sampleV(int sy) const {
  return (0.5 * (height_ - 1) - (sy - offsetPixels_)) * pitch_;
}

namespace {

// A uniform number in [0, 1) from (sample, ray, axis): a fixed seed per sample (SplitMix64 finaliser).
double jitter(std::uint64_t sample, std::uint64_t k, std::uint64_t axis) {
  std::uint64_t z =
      (sample * 0x9E3779B97F4A7C15ull) ^ (k * 0xBF58476D1CE4E5B9ull) ^ (axis * 0x94D049BB133111EBull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1p-53;
}

}  // namespace

Ray View::eyeRay(int sx, int sy, int k) const {
  double u = sampleU(sx), v = sampleV(sy);
  if (raysPerSample_ > 1) {
    // Stratified: a rows x columns grid over the footprint, one jittered ray per stratum.
    const int rows = int(std::sqrt(double(raysPerSample_)));
    const int columns = (raysPerSample_ + rows - 1) / rows;
    const std::uint64_t sample = sampleIndex(sx, sy);
    const double fx = ((k % columns) + jitter(sample, std::uint64_t(k), 0)) / columns - 0.5;
    const double fy = ((k / columns) + jitter(sample, std::uint64_t(k), 1)) / rows - 0.5;
    u += fx * pitch_;
    v -= fy * pitch_;
  }
  Ray ray;
  ray.origin = eye_;
  ray.direction = glm::normalize(forward_ + u * right_ + v * up_);
  ray.tMin = hither_;
  ray.tMax = kInfinity;
  return ray;
}

}  // namespace raycube::core
