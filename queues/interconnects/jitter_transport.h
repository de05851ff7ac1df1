#pragma once
// A Transport that wraps another and injects random delays (yields and short sleeps) around sends,
// receives and token passes: thread timings the scheduler would rarely produce, for the termination
// and determinism tests. Deterministic per seed in what it decides, not in how the OS then schedules.
#include <chrono>
#include <random>
#include <thread>

#include "node/transport.h"

namespace raycube::queues {

template <class Real>
class JitterTransport final : public node::BasicTransport<Real> {
 public:
  using Message = node::BasicRayMessage<Real>;
  JitterTransport(node::BasicTransport<Real>& inner, unsigned seed) : inner_(inner), random_(seed) {}

  std::size_t trySend(int neighbour, std::span<const Message> messages) override {
    jitter();
    const std::size_t sent = inner_.trySend(
        neighbour, messages.subspan(0, std::min<std::size_t>(messages.size(), 1 + random_() % 4)));
    jitter();
    return sent;
  }
  std::size_t receive(std::span<Message> into) override {
    jitter();
    return inner_.receive(into.subspan(0, std::min<std::size_t>(into.size(), 1 + random_() % 4)));
  }
  bool anyIncoming() const override { return inner_.anyIncoming(); }
  bool canSend(int neighbour) const override { return inner_.canSend(neighbour); }
  void sendContribution(const core::Contribution& c) override { inner_.sendContribution(c); }
  void flushContributions() override {
    jitter();
    inner_.flushContributions();
  }
  void countWaiting(std::ptrdiff_t change) override { inner_.countWaiting(change); }
  bool primariesHeld() const override { return inner_.primariesHeld(); }
  bool hasToken() const override { return inner_.hasToken(); }
  bool receiveToken(node::Token& token) override {
    jitter();
    return inner_.receiveToken(token);
  }
  void passToken(const node::Token& token) override {
    jitter();
    inner_.passToken(token);
    jitter();
  }
  void announceTermination() override { inner_.announceTermination(); }
  bool terminated() const override { return inner_.terminated(); }

 private:
  // Mostly nothing, sometimes a yield, rarely a sleep of up to 50 microseconds.
  void jitter() {
    const unsigned roll = random_() % 64;
    if (roll < 8) std::this_thread::yield();
    if (roll == 0) std::this_thread::sleep_for(std::chrono::microseconds(random_() % 50));
  }

  node::BasicTransport<Real>& inner_;
  std::minstd_rand random_;
};

}  // namespace raycube::queues
