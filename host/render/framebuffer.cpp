#include "host/render/framebuffer.h"

#include <cmath>
#include <cstddef>
#include <new>

#include "core/image.h"

namespace raycube::host {

using core::Color;
using core::Contribution;
using core::Image;
using core::Sampling;
using core::View;
namespace {

// Each contribution is rounded on its own; out-of-range values saturate instead of overflowing.
Framebuffer::Fixed toFixed(double value) {
  constexpr double kLimit = Framebuffer::kContributionLimit * Framebuffer::kFixedScale;
  const double scaled = value * Framebuffer::kFixedScale;
  if (scaled >= kLimit) return Framebuffer::Fixed(std::int64_t(kLimit));
  if (scaled <= -kLimit) return -Framebuffer::Fixed(std::int64_t(kLimit));
  return std::llround(scaled);
}

}  // namespace

Framebuffer::Framebuffer(int samplesX, int samplesY)
    : samplesX_(samplesX),
      samplesY_(samplesY),
      size_(std::size_t(samplesX) * std::size_t(samplesY) * 3),
      fixed_(static_cast<Fixed*>(std::calloc(size_, sizeof(Fixed)))) {
  static_assert(alignof(Fixed) <= alignof(std::max_align_t), "calloc's alignment must hold a Fixed");
  if (!fixed_ && size_ > 0) throw std::bad_alloc();
}

void Framebuffer::add(const Contribution& c) {
  Fixed* slot = &fixed_[std::size_t(c.sample) * 3];
  for (int ch = 0; ch < 3; ++ch)
    if (std::isfinite(c.value[ch])) slot[ch] += toFixed(c.value[ch]);
}

void Framebuffer::add(const Framebuffer& other) {
  for (std::size_t i = 0; i < size_; ++i) fixed_[i] += other.fixed_[i];
}

double Framebuffer::sampleChannel(std::size_t sample, int channel) const {
  return double(fixed_[sample * 3 + channel]) / kFixedScale;
}

Image Framebuffer::resolve(const View& view) const {
  Image image = Image::filled(view.width(), view.height());
  const bool corners = view.sampling() == Sampling::Corners;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      Color c(0);
      for (int ch = 0; ch < 3; ++ch) {
        if (corners) {
          // Sum the four corners in fixed point first, so the mean is exact up to one rounding.
          const Fixed sum =
              fixed_[view.sampleIndex(x, y) * 3 + ch] + fixed_[view.sampleIndex(x + 1, y) * 3 + ch] +
              fixed_[view.sampleIndex(x, y + 1) * 3 + ch] + fixed_[view.sampleIndex(x + 1, y + 1) * 3 + ch];
          c[ch] = double(sum) / (4 * kFixedScale);
        } else {
          c[ch] = sampleChannel(view.sampleIndex(x, y), ch);
        }
      }
      image.at(x, y) = c;
    }
  }
  return image;
}

}  // namespace raycube::host
