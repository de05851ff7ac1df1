#pragma once
// The machine's progress through its work. Rays are balanced between processors (3.7.1), but what a ray
// costs is not: where one region's rays cost several times the mean, a count of rays finished reads
// nearly done while that processor is far from its end. Each processor's part
// of the work is therefore its own sub-sampled estimate (host/prepare/load_estimate.h, ExpectedWork), and how
// much of that part is done is the share of its expected ray segments it has evaluated.
#include <cstdint>
#include <vector>

#include "host/prepare/load_estimate.h"

namespace raycube::host {

class MachineProgress {
 public:
  explicit MachineProgress(ExpectedWork expected);

  struct Work {
    double done = 0;      // in the estimate's units of work
    double expected = 0;  // all of it
  };
  // segmentsEvaluated: per processor, in processor order (missing ones have done nothing). A processor
  // that has evaluated all its expected segments counts as done (the estimate may be short; Progress
  // never shows 100% before the end).
  Work workOf(const std::vector<std::uint64_t>& segmentsEvaluated) const;

 private:
  ExpectedWork expected_;
  double total_ = 0;
};

}  // namespace raycube::host
