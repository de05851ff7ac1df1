#pragma once
// Priol & Bouatouch 3.1: the screen cut into pixel areas. Everything the machine partitions is a rectangle
// of sample indices; its faces are the planes through the eye at the sample boundaries, and the outermost
// boundaries are pushed to infinity so that the edge regions cover everything in front of the eye.
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
  }
  // axis 0: columns (s), axis 1: rows (q)
  double at(int axis, int k) const { return axis == 0 ? s_[k] : q_[k]; }
  int samples(int axis) const { return axis == 0 ? samplesX_ : samplesY_; }

 private:
  int samplesX_, samplesY_;
  std::vector<double> s_, q_;
};

}  // namespace raycube::node
