#pragma once
// A processor's incoming face FIFOs, one per neighbour (Priol & Bouatouch 3.2: a FIFO per face), read the
// way the shared-memory and MPI transports read them.
#include <cstddef>
#include <span>
#include <vector>

namespace raycube::queues {

// Takes as many rays as fit from the FIFOs, starting each call at the next neighbour in turn, so that a
// busy neighbour never starves the others.
class FaceFifoInbox {
 public:
  template <class Queue, class Message>
  std::size_t receive(const std::vector<Queue*>& incoming, std::span<Message> into) {
    std::size_t n = 0;
    const std::size_t count = incoming.size();
    for (std::size_t k = 0; k < count && n < into.size(); ++k)
      n += incoming[(next_ + k) % count]->tryPopN(into.subspan(n));
    if (count > 0) next_ = (next_ + 1) % count;  // fairness between neighbours
    return n;
  }

  template <class Queue>
  static bool anyIncoming(const std::vector<Queue*>& incoming) {
    for (const Queue* q : incoming)
      if (q->hasMessage()) return true;
    return false;
  }

 private:
  std::size_t next_ = 0;  // the neighbour slot the next call starts at
};

}  // namespace raycube::queues
