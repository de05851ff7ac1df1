#include "host/prepare/bsp_partition.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace raycube::host {
namespace {

constexpr int kCoarseCandidates = 32;
// A cut piece crossing at most this many lines is weighed line by line, exactly as costOfPiece says; a
// longer one as a linear function of the line, whose slope is then at most its weight over this.
constexpr long long kLinesWeighedOneByOne = 8;

// Sums over the lines first ... last, each added to a range of lines at once and read in one pass. A line
// no addition reached sums to exactly zero (what is added and later taken away need not cancel exactly).
class LineSums {
 public:
  LineSums(int first, int last)
      : first_(first),
        last_(last),
        steps_(std::size_t(std::max(0, last - first + 1)) + 1),
        reached_(steps_.size()) {}
  // Adds v to every line k with from <= k <= to.
  void add(double from, double to, double v) {
    from = std::max(from, double(first_));
    to = std::min(to, double(last_));
    if (!(from <= to)) return;  // also a NaN end: added nowhere
    const std::size_t begin = std::size_t(from) - std::size_t(first_),
                      end = std::size_t(to) - std::size_t(first_) + 1;
    steps_[begin] += v;
    steps_[end] -= v;
    ++reached_[begin];
    --reached_[end];
  }
  std::vector<double> totals() const {
    std::vector<double> out(steps_.size() - 1);
    double running = 0;
    long long reaching = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
      running += steps_[i];
      reaching += reached_[i];
      out[i] = reaching > 0 ? running : 0;
    }
    return out;
  }

 private:
  int first_, last_;
  std::vector<double> steps_;
  std::vector<long long> reached_;
};

struct Splitter {
  LoadMetric metric;
  std::vector<node::SampleRect> leaves;
  bool spareCore;                   // the next cut may hand one of its sides to another core
  std::uint64_t piecesWeighed = 0;  // the host's work: pieces weighed at the lines, then clipped to a side

  void split(const node::SampleRect& r, int processors, const std::vector<ScreenSegment>& pieces) {
    if (processors == 1) {
      leaves.push_back(r);
      return;
    }
    const int axis = cutAxis(r, processors);
    const std::pair<int, int> cut = bestCut(r, processors, pieces, axis);
    piecesWeighed += 3 * pieces.size();  // weighed across the lines once, clipped to each side
    const int best = cut.first, p1 = cut.second, p2 = processors - p1;
    node::SampleRect first = r, second = r;
    (axis == 0 ? first.x1 : first.y1) = best;
    (axis == 0 ? second.x0 : second.y0) = best;
    if (!spareCore) {
      split(first, p1, clipAll(pieces, first, Side{axis, double(best), false}));
      split(second, p2, clipAll(pieces, second, Side{axis, double(best), true}));
      return;
    }
    // The first cut's two sides on two cores (every later cut stays on its side's core): each is cut exactly
    // as it would be alone, and its leaves come before the second's, the same partition however many cores
    // ran it. On one core alone, the other waited idle through this part of the preparation.
    Splitter before{metric, {}, false}, beyond{metric, {}, false};
    std::future<void> beforeDone = std::async(std::launch::async, [&] {
      before.split(first, p1, clipAll(pieces, first, Side{axis, double(best), false}));
    });
    beyond.split(second, p2, clipAll(pieces, second, Side{axis, double(best), true}));
    beforeDone.get();
    for (const Splitter* side : {&before, &beyond}) {
      leaves.insert(leaves.end(), side->leaves.begin(), side->leaves.end());
      piecesWeighed += side->piecesWeighed;
    }
  }

  // Cut across the longer side, unless the shorter one is the only one that can hold both halves.
  static int cutAxis(const node::SampleRect& r, int processors) {
    int axis = r.width() >= r.height() ? 0 : 1;
    auto fits = [&](int ax) {
      const int length = ax == 0 ? r.width() : r.height(), across = ax == 0 ? r.height() : r.width();
      return length >= 2 && (long long)length * across >= processors;
    };
    if (!fits(axis)) axis = 1 - axis;
    return axis;
  }

  // Section 3.7.1: the line across `axis` that leaves both sides the same estimated load per processor, and
  // how many processors the side before it takes.
  std::pair<int, int> bestCut(const node::SampleRect& r, int processors,
                              const std::vector<ScreenSegment>& pieces, int axis) const {
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
    const LineLoads loads = loadsAcrossLines(pieces, axis, lo, hi, metric);
    // The best feasible line among `lines` in order (the first of equals).
    auto consider = [&](const std::vector<int>& lines) {
      for (int k : lines) {
        const int first = firstSide(k), second = processors - first;
        if (first == 0) continue;
        const double below = loads.below[std::size_t(k - lo - 1)],
                     above = loads.above[std::size_t(k - lo - 1)];
        // Equal load per processor on both sides; with no load at all, equal area per processor.
        const double imbalance = (below + above > 0)
                                     ? std::abs(below * second - above * first)
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
    return {best, p1};
  }

  // One side of a cut: the line `at` across `axis`, the side beyond it or before it.
  struct Side {
    int axis;
    double at;
    bool beyond;
  };
  // The pieces' parts inside r. Given the side of its parent's cut r lies on, a piece lying on the other
  // side, clear of the line by more than rounding, is passed over unclipped: the clip would drop it (its
  // parameter range along the line's normal ends a relative 1e-12 or more before the line).
  std::vector<ScreenSegment> clipAll(const std::vector<ScreenSegment>& pieces, const node::SampleRect& r,
                                     std::optional<Side> side = std::nullopt) const {
    const double margin = side ? 1e-9 * (1 + std::abs(side->at)) : 0;
    auto elsewhere = [&](const ScreenSegment& s) {
      if (!side) return false;
      const double a = side->axis == 0 ? s.x0 : s.y0, b = side->axis == 0 ? s.x1 : s.y1;
      return side->beyond ? std::max(a, b) < side->at - margin : std::min(a, b) > side->at + margin;
    };
    std::vector<ScreenSegment> kept;
    kept.reserve(pieces.size());
    ScreenSegment piece;
    for (const ScreenSegment& s : pieces)
      if (!elsewhere(s) && clipSegment(s, r.x0, r.y0, r.x1, r.y1, metric, piece)) kept.push_back(piece);
    return kept;
  }
};

}  // namespace

LineLoads loadsAcrossLines(const std::vector<ScreenSegment>& pieces, int axis, int lo, int hi,
                           LoadMetric metric) {
  const int first = lo + 1, last = hi - 1;
  LineSums below(first, last), above(first, last), slope(first, last);
  const double before = first - 1, beyond = last + 1;  // ranges reaching past the lines, kept finite
  for (const ScreenSegment& s : pieces) {
    const double a = axis == 0 ? s.x0 : s.y0, b = axis == 0 ? s.x1 : s.y1;
    const double pieceLo = std::min(a, b), pieceHi = std::max(a, b), w = s.weight;
    // The lines k past its low end (lo < k), and those up to its high end (k <= hi).
    const double pastLo = std::floor(std::clamp(pieceLo, before, beyond)) + 1;
    const double upToHi = std::floor(std::clamp(pieceHi, before, beyond));
    if (metric == LoadMetric::Rays) {
      below.add(pastLo, beyond, w);
      above.add(before, upToHi, w);
      continue;
    }
    // Whole above the lines k <= lo, whole below the lines k >= hi, cut by the lines between.
    const double lastAbove = pastLo - 1, cutFrom = pastLo;
    const double cutTo = std::ceil(std::clamp(pieceHi, before, beyond)) - 1;
    above.add(before, lastAbove, w);
    below.add(std::max(cutTo + 1, cutFrom), beyond, w);
    if (cutFrom > cutTo) continue;
    if (cutTo - cutFrom < kLinesWeighedOneByOne) {
      for (double k = std::max(cutFrom, double(first)); k <= std::min(cutTo, double(last)); ++k) {
        const double f = std::clamp((k - pieceLo) / (pieceHi - pieceLo), 0.0, 1.0);
        below.add(k, k, costOfPiece(w, f));
        above.add(k, k, costOfPiece(w, 1 - f));
      }
      continue;
    }
    // costOfPiece(w, (k - lo) / (hi - lo)) = 1 + rate (k - lo) below, its complement w - rate (k - lo) above.
    const double rate = (w - 1) / (pieceHi - pieceLo);
    below.add(cutFrom, cutTo, 1 - rate * pieceLo);
    above.add(cutFrom, cutTo, w + rate * pieceLo);
    slope.add(cutFrom, cutTo, rate);
  }
  LineLoads loads{below.totals(), above.totals()};
  const std::vector<double> rates = slope.totals();
  for (std::size_t i = 0; i < rates.size(); ++i) {
    const double k = double(first) + double(i);
    loads.below[i] += rates[i] * k;
    loads.above[i] -= rates[i] * k;
  }
  return loads;
}

std::vector<node::SampleRect> bspPartition(int samplesX, int samplesY, int processors,
                                           const LoadSample& sample, LoadMetric metric, int cores,
                                           std::uint64_t* piecesWeighed) {
  if (processors < 1 || (long long)samplesX * samplesY < processors)
    throw std::invalid_argument("BSP: more processors than samples");
  Splitter splitter{metric, {}, (cores > 0 ? unsigned(cores) : std::thread::hardware_concurrency()) > 1};
  const node::SampleRect screen{0, samplesX, 0, samplesY};
  splitter.split(screen, processors, splitter.clipAll(sample.segments, screen));
  if (piecesWeighed) *piecesWeighed = sample.segments.size() + splitter.piecesWeighed;
  return splitter.leaves;
}

}  // namespace raycube::host
