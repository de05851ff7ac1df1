#pragma once
// The host's frame buffer (Priol & Bouatouch 3.4, 3.5.1): contributions arrive in any order from any
// number of processors, so each is rounded once to fixed point and integer sums make the image
// independent of arrival order, thread count and partition, bit for bit.
#include <cstdint>
#include <cstdlib>
#include <memory>

#include "core/contribution_sink.h"
#include "core/ray.h"
#include "core/view.h"

namespace raycube::core {
struct Image;
}

namespace raycube::host {

class Framebuffer final : public core::ContributionSink {
 public:
  // 2^-40 resolution (~1e-12); one contribution saturates at 2^22 (kContributionLimit). Sums are kept in
  // 128 bits: 2^65 saturated contributions fit in a slot, so no sum ever wraps and, integer addition being
  // associative, saturation does not depend on arrival order (a saturating 64-bit add would).
  static constexpr double kFixedScale = 0x1p40;
  static constexpr double kContributionLimit = 0x1p22;
  using Fixed = __int128;

  Framebuffer(int samplesX, int samplesY);

  // Not synchronised: one writer per sample at a time (the host thread, or the task owning the sample).
  // A NaN or infinite channel is dropped (tracing counts such contributions as nonFinite).
  void add(const core::Contribution& c) override;
  void add(const Framebuffer& other);  // sum of two partial buffers of the same size

  // Pixel colours: the sample itself (centres) or the mean of a pixel's four corner samples (SPD rule 6).
  core::Image resolve(const core::View& view) const;

  int samplesX() const { return samplesX_; }
  int samplesY() const { return samplesY_; }

 private:
  double sampleChannel(std::size_t sample, int channel) const;

  // Zeroed by the allocator (calloc): a large buffer is fresh pages the kernel zeroes as they are first
  // touched, where a vector wrote 12.6 MB of zeros at 512 x 512 before the first ray.
  struct Free {
    void operator()(Fixed* p) const { std::free(p); }
  };
  int samplesX_, samplesY_;
  std::size_t size_;  // 3 channels per sample
  std::unique_ptr<Fixed[], Free> fixed_;
};

}  // namespace raycube::host
