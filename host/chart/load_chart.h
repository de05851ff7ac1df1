#pragma once
// The paper's figure 15 as a picture: for each processor the rays its load was estimated to be by
// sub-sampling beside the rays it actually processed, so a reader sees at a glance whether the estimate
// ranked the processors right (Priol & Bouatouch 4, figure 15).
#include <span>
#include <string>
#include <vector>

#include "host/chart/chart.h"

namespace raycube::host {

// Pearson correlation of two equally long series: how well the estimate predicts the actual load up to
// scale and offset. 0 when either series has zero variance (nothing to correlate). Throws
// std::invalid_argument when the series are empty or of different lengths.
double pearson(std::span<const double> a, std::span<const double> b);

// Each value over the series' mean; an all-zero (or empty) series is returned unchanged.
std::vector<double> normalisedToMean(std::span<const double> values);

// Figure 15 as a grouped bar chart, one group per processor: the load estimated from the sub-sampled rays
// beside the rays it actually processed, each normalised to its own mean (the two count different things,
// sampled rays against all rays, so the chart is about their shape; 1 is the average processor, as in the
// summary and --stats). Throws std::invalid_argument when the series are empty, of different lengths, or
// hold a negative or non-finite count.
BarChart loadChart(std::span<const double> estimated, std::span<const double> actual,
                   std::string caption = "");

}  // namespace raycube::host
