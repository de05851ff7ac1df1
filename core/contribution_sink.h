#pragma once
// Where the pieces of pixel colour go once a ray is shaded (Priol & Bouatouch 3.4): the host's frame
// buffer, a node's channel to the host, or nowhere (the load estimate only counts rays). Tracing knows
// only this interface; accumulation belongs to whoever owns the sink.
#include "core/ray.h"

namespace raycube::core {

class ContributionSink {
 public:
  virtual void add(const Contribution& contribution) = 0;

 protected:
  ~ContributionSink() = default;
};

// For tracing whose colours nobody reads (the sub-sampled load estimate, 3.7.1).
class DiscardContributions final : public ContributionSink {
 public:
  void add(const Contribution&) override {}
};

}  // namespace raycube::core
