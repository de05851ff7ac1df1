#pragma once
// The one interface between a node program and the rest of the machine (Priol & Bouatouch 3.5): rays to
// the neighbours across its faces (one FIFO per neighbour, 3.7.1 figure 10), rays from neighbours,
// contributions to the host, the termination token. Every call returns at once: the node never waits and
// never reads a clock; its driver does both (threads, SimGrid actors, MPI ranks), between steps. The node
// never sees how rays travel: the implementations live in queues/.
#include <cstddef>
#include <span>

#include "core/ray.h"
#include "node/ray_message.h"
#include "node/safra_termination.h"

namespace raycube::node {

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

  // Machine-wide back-pressure, where one memory holds every processor's waiting rays (shared memory):
  // the node reports each change of how many of its rays wait for room in a neighbour's FIFO, and shoots
  // no primary ray while primariesHeld(). A distributed machine (the iPSC, its emulation, MPI ranks) has no
  // such view: never held, as by default.
  virtual void countWaiting(std::ptrdiff_t /*change*/) {}
  virtual bool primariesHeld() const { return false; }

  virtual bool hasToken() const = 0;
  virtual bool receiveToken(Token& token) = 0;
  virtual void passToken(const Token& token) = 0;  // to the next node on the ring
  virtual void announceTermination() = 0;
  virtual bool terminated() const = 0;
};
using Transport = BasicTransport<double>;

}  // namespace raycube::node
