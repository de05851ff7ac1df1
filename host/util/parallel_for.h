#pragma once
// The host's preparation on every core (3.2 steps 1-2 are the host's, and the iPSC's host was one
// processor; ours has several, and the preprocessing share of a run is measured).
#include <algorithm>
#include <thread>
#include <vector>

namespace raycube::host {

// Calls visit(i) for every i in [0, count), on all cores (i, i + cores, ... per thread), and returns when
// all are done. std::thread, whose join ThreadSanitizer sees (oneTBB's, in Debian's uninstrumented build,
// it does not, and the host's later reads were reported). Results must not depend on which thread ran an i.
template <class Visit>
void parallelFor(int count, Visit&& visit) {
  const int workers = std::max(1, std::min(count, int(std::thread::hardware_concurrency())));
  if (workers == 1) {
    for (int i = 0; i < count; ++i) visit(i);
    return;
  }
  std::vector<std::jthread> threads;
  for (int w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      for (int i = w; i < count; i += workers) visit(i);
    });
}

}  // namespace raycube::host
