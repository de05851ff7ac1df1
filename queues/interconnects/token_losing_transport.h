#pragma once
// A Transport that wraps another and drops every termination token it is asked to pass: a machine that can
// never prove termination, for the tests of the engines' watchdog (host/engines/stall_watch.h).
#include "node/transport.h"

namespace raycube::queues {

template <class Real>
class TokenLosingTransport final : public node::BasicTransport<Real> {
 public:
  using Message = node::BasicRayMessage<Real>;
  explicit TokenLosingTransport(node::BasicTransport<Real>& inner) : inner_(inner) {}

  std::size_t trySend(int neighbour, std::span<const Message> messages) override {
    return inner_.trySend(neighbour, messages);
  }
  std::size_t receive(std::span<Message> into) override { return inner_.receive(into); }
  bool anyIncoming() const override { return inner_.anyIncoming(); }
  bool canSend(int neighbour) const override { return inner_.canSend(neighbour); }
  void sendContribution(const core::Contribution& c) override { inner_.sendContribution(c); }
  void flushContributions() override { inner_.flushContributions(); }
  void countWaiting(std::ptrdiff_t change) override { inner_.countWaiting(change); }
  bool primariesHeld() const override { return inner_.primariesHeld(); }
  bool hasToken() const override { return inner_.hasToken(); }
  bool receiveToken(node::Token& token) override { return inner_.receiveToken(token); }
  void passToken(const node::Token&) override {}
  void announceTermination() override { inner_.announceTermination(); }
  bool terminated() const override { return inner_.terminated(); }

 private:
  node::BasicTransport<Real>& inner_;
};

}  // namespace raycube::queues
