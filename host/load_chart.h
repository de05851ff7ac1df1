#pragma once
// The paper's figure 15 as a picture: for each processor the rays its load was estimated to be by
// sub-sampling beside the rays it actually processed, so a reader sees at a glance whether the estimate
// ranked the processors right (Priol & Bouatouch 4, figure 15).
#include <span>

#include "core/image.h"

namespace raycube::host {

// Pearson correlation of two equally long series: how well the estimate predicts the actual load up to
// scale and offset. 0 when either series has zero variance (nothing to correlate). Throws
// std::invalid_argument when the series are empty or of different lengths.
double pearson(std::span<const double> a, std::span<const double> b);

// Bar colours (linear RGB), exposed so tests and callers can find the bars in the picture.
inline const core::Color kEstimatedBarColor{0.05, 0.25, 0.80};  // blue
inline const core::Color kActualBarColor{0.90, 0.35, 0.02};     // orange

// Grouped bar chart, one slot per processor: estimated (blue) on the left, actual (orange) on the right.
// Each series is normalised to its own maximum, so the tallest bar of each reaches the top of the scale:
// the two series count different things (sampled rays versus all rays), and the chart is about their
// shape, not their scale. Grid lines mark 0.25 steps of that scale; a legend of two coloured squares
// (estimated, then actual) sits in the top-right corner; there is no text. White background, 320 pixels
// high, max(480, 24 per processor + margins) wide. Throws std::invalid_argument when the series are empty,
// of different lengths, or hold a negative or non-finite count.
core::Image loadChart(std::span<const double> estimated, std::span<const double> actual);

}  // namespace raycube::host
