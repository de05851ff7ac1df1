#pragma once
// The host's frame buffer (Priol & Bouatouch 3.4, 3.5.1): contributions arrive in any order from any
// number of processors, so each is rounded once to 64-bit fixed point and integer sums make the image
// independent of arrival order, thread count and partition, bit for bit.
#include <cstdint>
#include <vector>

#include "core/contribution_sink.h"
#include "core/ray.h"
#include "core/view.h"

namespace raycube::core {

struct Image;

class Framebuffer final : public ContributionSink {
 public:
  // 2^-40 resolution (~1e-12) and headroom up to 2^23 per channel and sample.
  static constexpr double kFixedScale = 0x1p40;

  Framebuffer(int samplesX, int samplesY);

  // Not synchronised: one writer per sample at a time (the host thread, or the task owning the sample).
  // A NaN or infinite channel is dropped (tracing counts such contributions as nonFinite).
  void add(const Contribution& c) override;
  void add(const Framebuffer& other);  // sum of two partial buffers of the same size

  // Pixel colours: the sample itself (centres) or the mean of a pixel's four corner samples (SPD rule 6).
  Image resolve(const View& view) const;

  int samplesX() const { return samplesX_; }
  int samplesY() const { return samplesY_; }

 private:
  double sampleChannel(std::size_t sample, int channel) const;

  int samplesX_, samplesY_;
  std::vector<std::int64_t> fixed_;  // 3 channels per sample
};

}  // namespace raycube::core
