#pragma once
// A Transport that wraps another and never returns from the first contribution its processor sends: a step
// that does not end (a walk that loops), for the tests of the engines' watchdogs (host/engines/
// stall_watch.h). Only the end of the process stops it.
#include <chrono>
#include <thread>

#include "node/transport.h"

namespace raycube::queues {

template <class Real>
class StepStallingTransport final : public node::BasicTransport<Real> {
 public:
  using Message = node::BasicRayMessage<Real>;
  explicit StepStallingTransport(node::BasicTransport<Real>& inner) : inner_(inner) {}

  std::size_t trySend(int neighbour, std::span<const Message> messages) override {
    return inner_.trySend(neighbour, messages);
  }
  std::size_t receive(std::span<Message> into) override { return inner_.receive(into); }
  bool anyIncoming() const override { return inner_.anyIncoming(); }
  bool canSend(int neighbour) const override { return inner_.canSend(neighbour); }
  [[noreturn]] void sendContribution(const core::Contribution&) override {
    for (;;) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  void flushContributions() override { inner_.flushContributions(); }
  void countWaiting(std::ptrdiff_t change) override { inner_.countWaiting(change); }
  bool primariesHeld() const override { return inner_.primariesHeld(); }
  bool hasToken() const override { return inner_.hasToken(); }
  bool receiveToken(node::Token& token) override { return inner_.receiveToken(token); }
  void passToken(const node::Token& token) override { inner_.passToken(token); }
  void announceTermination() override { inner_.announceTermination(); }
  bool terminated() const override { return inner_.terminated(); }

 private:
  node::BasicTransport<Real>& inner_;
};

}  // namespace raycube::queues
