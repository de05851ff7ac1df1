#pragma once
// Priol & Bouatouch 3.7.1, step 2: a 2D binary space partition of the screen (Fuchs 1980) into P regions
// holding roughly equal loads of projected ray segments. A segment crossing a splitting line is split in
// two (figure 9). P need not be a power of two: a region meant for P processors is cut in the ratio
// floor(P/2) : ceil(P/2) where the cut leaves both sides enough samples, at the line that best equalises
// load per processor.
#include <vector>

#include "host/load_estimate.h"
#include "node/screen_grid.h"

namespace raycube::host {

std::vector<node::SampleRect> bspPartition(int samplesX, int samplesY, int processors,
                                           const LoadSample& sample, LoadMetric metric);

}  // namespace raycube::host
