#pragma once
// What a render produced: the image, the timings SPD rule 12 asks for, and the counts.
#include <string>

#include "core/image.h"
#include "core/precision.h"
#include "core/trace_stats.h"

namespace raycube::host {

struct RenderResult {
  core::Image image;
  core::TraceCounters counters;
  double preprocessSeconds = 0;  // database, acceleration structures, partitioning
  double traceSeconds = 0;       // tracing and accumulation
  std::string mode;
  int workers = 1;
  core::Precision precision = core::Precision::Double;
};

}  // namespace raycube::host
