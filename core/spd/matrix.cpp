#include "core/spd/matrix.h"

#include <cmath>

namespace raycube::core {

SpdMatrix spdIdentity() {
  return {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
}

SpdMatrix spdRotation(SpdAxis axis, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  switch (axis) {
    case SpdAxis::X:
      return {{{1, 0, 0, 0}, {0, c, s, 0}, {0, -s, c, 0}, {0, 0, 0, 1}}};
    case SpdAxis::Y:
      return {{{c, 0, -s, 0}, {0, 1, 0, 0}, {s, 0, c, 0}, {0, 0, 0, 1}}};
    case SpdAxis::Z:
      break;
  }
  return {{{c, s, 0, 0}, {-s, c, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
}

SpdMatrix spdAxisRotation(const Vec3& a, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double t = 1.0 - c;
  return {{{a.x * a.x + (1.0 - a.x * a.x) * c, a.x * a.y * t + a.z * s, a.x * a.z * t - a.y * s, 0},
           {a.x * a.y * t - a.z * s, a.y * a.y + (1.0 - a.y * a.y) * c, a.y * a.z * t + a.x * s, 0},
           {a.x * a.z * t + a.y * s, a.y * a.z * t - a.x * s, a.z * a.z + (1.0 - a.z * a.z) * c, 0},
           {0, 0, 0, 1}}};
}

SpdMatrix spdTranslation(const Vec3& offset) {
  SpdMatrix m = spdIdentity();
  m[3] = {offset.x, offset.y, offset.z, 1};
  return m;
}

SpdMatrix spdScaling(const Vec3& factors) {
  return {{{factors.x, 0, 0, 0}, {0, factors.y, 0, 0}, {0, 0, factors.z, 0}, {0, 0, 0, 1}}};
}

SpdMatrix spdProduct(const SpdMatrix& first, const SpdMatrix& then) {
  SpdMatrix result{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      result[i][j] = first[i][0] * then[0][j] + first[i][1] * then[1][j] + first[i][2] * then[2][j] +
                     first[i][3] * then[3][j];
    }
  }
  return result;
}

Vec3 spdTransformVector(const Vec3& v, const SpdMatrix& m) {
  return Vec3(v.x * m[0][0] + v.y * m[1][0] + v.z * m[2][0], v.x * m[0][1] + v.y * m[1][1] + v.z * m[2][1],
              v.x * m[0][2] + v.y * m[1][2] + v.z * m[2][2]);
}

Vec3 spdTransformPoint(const Vec3& p, const SpdMatrix& m) {
  return Vec3(p.x * m[0][0] + p.y * m[1][0] + p.z * m[2][0] + m[3][0],
              p.x * m[0][1] + p.y * m[1][1] + p.z * m[2][1] + m[3][1],
              p.x * m[0][2] + p.y * m[1][2] + p.z * m[2][2] + m[3][2]);
}

Vec3 spdNormalized(const Vec3& v) {
  const double length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return length > 0.0 ? Vec3(v.x / length, v.y / length, v.z / length) : v;
}

double spdScaleOf(const SpdMatrix& m) {
  const double w = m[3][3];
  const Vec3 row(m[0][0] / w, m[0][1] / w, m[0][2] / w);
  return std::sqrt(row.x * row.x + row.y * row.y + row.z * row.z);
}

}  // namespace raycube::core
