#pragma once
// Priol & Bouatouch 3.1: the screen cut into pixel areas. Everything the machine partitions is a rectangle
// of sample indices; its faces are the planes through the eye at the sample boundaries, and the outermost
// boundaries are pushed to infinity so that the edge regions cover everything in front of the eye.
#include <cmath>
#include <vector>

#include "core/tolerances.h"
#include "core/view.h"

namespace raycube::node {

// A rectangle of samples [x0, x1) x [y0, y1).
struct SampleRect {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  long long count() const { return (long long)width() * height(); }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// Where a rectangle of samples lies on the screen: [s0, s1) x [q0, q1), its faces' coordinates (outermost
// ones at infinity).
struct ScreenRect {
  double s0 = 0, s1 = 0, q0 = 0, q1 = 0;
};

// Screen coordinates of sample boundaries; boundary 0 and boundary N are at infinity.
class ScreenLines {
 public:
  explicit ScreenLines(const core::View& view) : samplesX_(view.samplesX()), samplesY_(view.samplesY()) {
    s_.resize(samplesX_ + 1);
    q_.resize(samplesY_ + 1);
    for (int k = 0; k <= samplesX_; ++k) s_[k] = view.boundaryU(k);
    for (int k = 0; k <= samplesY_; ++k) q_[k] = -view.boundaryV(k);
    s_.front() = q_.front() = -core::kInfinity;
    s_.back() = core::kInfinity;
    q_.back() = core::kInfinity;
    for (int axis = 0; axis < 2; ++axis) {
      const std::vector<double>& lines = axis == 0 ? s_ : q_;
      const int interior = int(lines.size()) - 2;  // boundaries 1 .. samples - 1 are finite
      first_[axis] = interior > 0 ? lines[1] : 0.0;
      perStep_[axis] = interior > 1 ? (interior - 1) / (lines[interior] - lines[1]) : 0.0;
    }
  }
  // axis 0: columns (s), axis 1: rows (q)
  double at(int axis, int k) const { return axis == 0 ? s_[k] : q_[k]; }
  int samples(int axis) const { return axis == 0 ? samplesX_ : samplesY_; }
  ScreenRect around(const SampleRect& a) const {
    return {at(0, a.x0), at(0, a.x1), at(1, a.y0), at(1, a.y1)};
  }

  // The sample k in [lo, hi) whose boundaries hold value (at(k) <= value < at(k + 1)), clamped to the range;
  // lo for NaN. The boundaries are evenly spaced: a guess from the spacing, corrected against the table (a
  // binary search reads a cold table ten times per region a ray leaves, a visible share of a run).
  int sampleIndex(int axis, double value, int lo, int hi) const {
    if (!(value == value)) return lo;
    const double guess = std::floor(1.0 + (value - first_[axis]) * perStep_[axis]);  // NaN for inf * 0
    int k = guess >= hi - 1 ? hi - 1 : guess > lo ? int(guess) : lo;
    while (k + 1 < hi && at(axis, k + 1) <= value) ++k;
    while (k > lo && !(at(axis, k) <= value)) --k;
    return k;
  }

 private:
  int samplesX_, samplesY_;
  std::vector<double> s_, q_;
  double first_[2], perStep_[2];  // boundary 1 and boundaries per unit, per axis
};

}  // namespace raycube::node
