#pragma once
// The one interface between a node program and the rest of the machine (Priol & Bouatouch 3.5): rays to
// the neighbours across its faces (one FIFO per neighbour, 3.7.1 figure 10), rays from neighbours,
// contributions to the host, the termination token. The node never sees how these travel; shared-memory FIFOs
// are one implementation, MPI could be another.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "core/ray.h"
#include "node/ray_message.h"

namespace raycube::node {

// Safra's variant of the Dijkstra-Feijen-van Gasteren token (EWD 998), see LogicalProcessor.
struct Token {
  bool black = false;
  std::int64_t count = 0;   // sum of (messages sent - messages received) of the nodes visited
  std::uint32_t round = 0;  // probes started by node 0
};

template <class Real>
class BasicTransport {
 public:
  using Message = BasicRayMessage<Real>;
  virtual ~BasicTransport() = default;

  // Sends the longest prefix of `messages` the FIFO to that neighbouring processor has room for; returns
  // its length. The caller keeps the rest and tries again later.
  virtual std::size_t trySend(int neighbour, std::span<const Message> messages) = 0;
  // Up to into.size() rays from the incoming FIFOs; returns how many.
  virtual std::size_t receive(std::span<Message> into) = 0;
  virtual bool anyIncoming() const = 0;
  virtual bool canSend(int neighbour) const = 0;

  // Contributions are batched and shipped when a block fills or on flush (when the node goes idle).
  virtual void sendContribution(const core::Contribution& contribution) = 0;
  virtual void flushContributions() = 0;

  virtual bool hasToken() const = 0;
  virtual bool receiveToken(Token& token) = 0;
  virtual void passToken(const Token& token) = 0;  // to the next node on the ring
  virtual void announceTermination() = 0;
  virtual bool terminated() const = 0;

  // Sleep (after a short spin) until ready() holds; any arriving ray, token or termination re-checks it.
  virtual void waitUntil(const std::function<bool()>& ready) = 0;
};
using Transport = BasicTransport<double>;

}  // namespace raycube::node
