#include "host/bsp_partition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "host/parallel_for.h"

namespace raycube::host {
namespace {

constexpr int kCoarseCandidates = 32;
// Pieces times candidate lines above which the candidates are weighed on all cores.
constexpr std::size_t kParallelWork = 1 << 18;

struct Splitter {
  LoadMetric metric;
  std::vector<node::SampleRect> leaves;

  // The pieces' extents along the axis being cut, side by side (lo <= hi), with their weights: every
  // candidate line reads them in the pieces' order.
  struct Extents {
    std::vector<double> lo, hi, weight;
  };
  static Extents extentsAlong(const std::vector<ScreenSegment>& pieces, int axis) {
    Extents e;
    for (auto* v : {&e.lo, &e.hi, &e.weight}) v->reserve(pieces.size());
    for (const ScreenSegment& s : pieces) {
      const double a = axis == 0 ? s.x0 : s.y0, b = axis == 0 ? s.x1 : s.y1;
      e.lo.push_back(std::min(a, b));
      e.hi.push_back(std::max(a, b));
      e.weight.push_back(s.weight);
    }
    return e;
  }

  // Load on each side of the line k (summed in locals: the callers' outputs sit side by side, written by
  // different threads), piece by piece in order, so the sums are the same whoever computes them.
  void sides(const Extents& e, double k, double& belowOut, double& aboveOut) const {
    double below = 0, above = 0;
    const std::size_t n = e.lo.size();
    if (metric == LoadMetric::Rays) {
      for (std::size_t i = 0; i < n; ++i) {
        below += e.lo[i] < k ? e.weight[i] : 0;
        above += e.hi[i] >= k ? e.weight[i] : 0;
      }
    } else {
      // A piece on one side of the line weighs there whole; a piece the line cuts weighs on each side what
      // clipping it there would give it (costOfPiece: one each, the work share by length).
      for (std::size_t i = 0; i < n; ++i) {
        const double lo = e.lo[i], hi = e.hi[i], w = e.weight[i];
        if (lo >= k) {
          above += w;
        } else if (hi <= k) {
          below += w;
        } else {
          const double f = std::clamp((k - lo) / (hi - lo), 0.0, 1.0);
          below += costOfPiece(w, f);
          above += costOfPiece(w, 1 - f);
        }
      }
    }
    belowOut = below;
    aboveOut = above;
  }

  void split(const node::SampleRect& r, int processors, const std::vector<ScreenSegment>& pieces) {
    if (processors == 1) {
      leaves.push_back(r);
      return;
    }
    // Cut across the longer side, unless the shorter one is the only one that can hold both halves.
    int axis = r.width() >= r.height() ? 0 : 1;
    auto fits = [&](int ax) {
      const int length = ax == 0 ? r.width() : r.height(), across = ax == 0 ? r.height() : r.width();
      return length >= 2 && (long long)length * across >= processors;
    };
    if (!fits(axis)) axis = 1 - axis;
    const int lo = axis == 0 ? r.x0 : r.y0, hi = axis == 0 ? r.x1 : r.y1;
    const long long across = axis == 0 ? r.height() : r.width();
    int best = -1, p1 = 0;
    double bestImbalance = std::numeric_limits<double>::infinity();
    // Processors each side of line k can take: at least one sample each. Prefer halving the count (ratio
    // floor(P/2) : ceil(P/2)); shift it only when the cut leaves one side too few samples. 0: none fits.
    auto firstSide = [&](int k) {
      const long long most = std::min<long long>(processors - 1, (k - lo) * across);
      const long long least = std::max<long long>(1, processors - (hi - k) * across);
      return least > most ? 0 : int(std::clamp<long long>(processors / 2, least, most));
    };
    const Extents extents = extentsAlong(pieces, axis);
    // The loads each side of every feasible line among `lines`, then the best in order (the first of equals).
    auto consider = [&](const std::vector<int>& lines) {
      std::vector<int> feasible;
      for (int k : lines)
        if (firstSide(k) > 0) feasible.push_back(k);
      std::vector<double> below(feasible.size()), above(feasible.size());
      auto weigh = [&](int i) {
        const auto at = std::size_t(i);
        sides(extents, feasible[at], below[at], above[at]);
      };
      if (pieces.size() * feasible.size() >= kParallelWork)
        parallelFor(int(feasible.size()), weigh);
      else
        for (int i = 0; i < int(feasible.size()); ++i) weigh(i);
      for (std::size_t i = 0; i < feasible.size(); ++i) {
        const int k = feasible[i], first = firstSide(k), second = processors - first;
        // Equal load per processor on both sides; with no load at all, equal area per processor.
        const double imbalance = (below[i] + above[i] > 0)
                                     ? std::abs(below[i] * second - above[i] * first)
                                     : std::abs(double(k - lo) * second - double(hi - k) * first);
        if (imbalance < bestImbalance) {
          bestImbalance = imbalance;
          best = k;
          p1 = first;
        }
      }
    };
    auto range = [](int from, int to, int step) {
      std::vector<int> lines;
      for (int k = from; k < to; k += step) lines.push_back(k);
      return lines;
    };
    // Coarse to fine: every step-th line, then every line around the best one (loads vary smoothly).
    const int step = std::max(1, (hi - lo) / kCoarseCandidates);
    consider(range(lo + 1, hi, step));
    const int coarse = best < 0 ? lo + 1 : best;
    consider(range(std::max(lo + 1, coarse - step), std::min(hi, coarse + step + 1), 1));
    for (int k = lo + 1; best < 0 && k < hi; ++k) consider({k});  // feasible lines may all lie between
    if (best < 0) throw std::invalid_argument("BSP: an area is too small for its processors");
    const int p2 = processors - p1;
    node::SampleRect first = r, second = r;
    (axis == 0 ? first.x1 : first.y1) = best;
    (axis == 0 ? second.x0 : second.y0) = best;
    split(first, p1, clipAll(pieces, first));
    split(second, p2, clipAll(pieces, second));
  }

  std::vector<ScreenSegment> clipAll(const std::vector<ScreenSegment>& pieces,
                                     const node::SampleRect& r) const {
    std::vector<ScreenSegment> kept;
    ScreenSegment piece;
    for (const ScreenSegment& s : pieces)
      if (clipSegment(s, r.x0, r.y0, r.x1, r.y1, metric, piece)) kept.push_back(piece);
    return kept;
  }
};

}  // namespace

std::vector<node::SampleRect> bspPartition(int samplesX, int samplesY, int processors,
                                           const LoadSample& sample, LoadMetric metric) {
  if (processors < 1 || (long long)samplesX * samplesY < processors)
    throw std::invalid_argument("BSP: more processors than samples");
  Splitter splitter{metric, {}};
  const node::SampleRect screen{0, samplesX, 0, samplesY};
  splitter.split(screen, processors, splitter.clipAll(sample.segments, screen));
  return splitter.leaves;
}

}  // namespace raycube::host
