#pragma once
// Priol & Bouatouch 3.7.1, step 2: a 2D binary space partition of the screen (Fuchs 1980) into P regions
// holding roughly equal loads of projected ray segments. A segment crossing a splitting line is split in
// two (figure 9). P need not be a power of two: a region meant for P processors is cut in the ratio
// floor(P/2) : ceil(P/2) where the cut leaves both sides enough samples, at the line that best equalises
// load per processor.
#include <cstdint>
#include <vector>

#include "host/prepare/load_estimate.h"
#include "node/screen_grid.h"

namespace raycube::host {

// cores: how many the cutting may use (0: the host's); the partition is the same for any number.
// piecesWeighed, if given: the segment pieces the cuts weighed and clipped (the host's work, HostWork).
std::vector<node::SampleRect> bspPartition(int samplesX, int samplesY, int processors,
                                           const LoadSample& sample, LoadMetric metric, int cores = 0,
                                           std::uint64_t* piecesWeighed = nullptr);

// The load on each side of every candidate line of an area [lo, hi) along `axis` (0: x, the lines x = k;
// 1: y), k = lo + 1 ... hi - 1: below[k - lo - 1] and above[k - lo - 1]. As the BSP weighs a line: the ray
// metric counts a piece on every side it reaches (lo < k below, hi >= k above); the cost metric counts a
// piece whole on the side it lies, and a piece the line cuts on both sides by costOfPiece. One pass over the
// pieces and one over the lines, where weighing each line apart read every piece once per line.
struct LineLoads {
  std::vector<double> below, above;
};
LineLoads loadsAcrossLines(const std::vector<ScreenSegment>& pieces, int axis, int lo, int hi,
                           LoadMetric metric);

}  // namespace raycube::host
