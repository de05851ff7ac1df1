#include "core/view.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/tolerances.h"

namespace raycube::core {

View::View(const Camera& camera, int width, int height, Sampling sampling)
    : width_(width), height_(height), sampling_(sampling), eye_(camera.from), hither_(camera.hither) {
  if (width < 1 || height < 1) throw std::invalid_argument("image size must be at least 1x1");
  const bool corners = sampling == Sampling::Corners;
  samplesX_ = width + (corners ? 1 : 0);
  samplesY_ = height + (corners ? 1 : 0);
  offsetPixels_ = corners ? 0.5 : 0.0;
  forward_ = glm::normalize(camera.at - camera.from);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
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

Ray View::eyeRay(int sx, int sy) const {
  Ray ray;
  ray.origin = eye_;
  ray.direction = glm::normalize(forward_ + sampleU(sx) * right_ + sampleV(sy) * up_);
  ray.tMin = hither_;
  ray.tMax = kInfinity;
  return ray;
}

Vec3 View::toEye(const Vec3& world) const {
  return directionToEye(world - eye_);
}
Vec3 View::directionToEye(const Vec3& d) const {
  return Vec3(glm::dot(d, right_), glm::dot(d, up_), glm::dot(d, forward_));
}

}  // namespace raycube::core
