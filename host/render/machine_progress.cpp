#include "host/render/machine_progress.h"

#include <algorithm>
#include <numeric>

namespace raycube::host {

MachineProgress::MachineProgress(ExpectedWork expected)
    : expected_(std::move(expected)),
      total_(std::accumulate(expected_.work.begin(), expected_.work.end(), 0.0)) {}

MachineProgress::Work MachineProgress::workOf(const std::vector<std::uint64_t>& segmentsEvaluated) const {
  Work w;
  w.expected = total_;
  for (std::size_t p = 0; p < expected_.work.size(); ++p) {
    const double evaluated = p < segmentsEvaluated.size() ? double(segmentsEvaluated[p]) : 0.0;
    const double expected = expected_.segments[p];
    const double share = expected > 0 ? std::min(1.0, evaluated / expected) : evaluated > 0 ? 1.0 : 0.0;
    w.done += share * expected_.work[p];
  }
  return w;
}

}  // namespace raycube::host
