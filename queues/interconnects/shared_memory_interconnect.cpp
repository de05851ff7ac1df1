#include "queues/interconnects/shared_memory_interconnect.h"

#include <algorithm>
#include <stdexcept>

#include "queues/interconnects/face_fifo_inbox.h"

namespace raycube::queues {
namespace {

std::vector<Doorbell*> rawBells(const std::vector<std::unique_ptr<Doorbell>>& bells) {
  std::vector<Doorbell*> raw;
  for (const auto& b : bells) raw.push_back(b.get());
  return raw;
}

// The slots of every FIFO: one per directed adjacency.
std::size_t fifoSlotsOf(const node::RegionMap& regions, std::size_t queueCapacity) {
  std::size_t fifos = 0;
  for (int p = 0; p < regions.processors(); ++p) fifos += regions.neighbours(p).size();
  return fifos * spscSlotsFor(queueCapacity);
}

}  // namespace

template <class Real>
class SharedMemoryInterconnect<Real>::Endpoint final : public node::BasicTransport<Real> {
 public:
  using Message = node::BasicRayMessage<Real>;
  Endpoint(SharedMemoryInterconnect& machine, int id)
      : machine_(machine),
        id_(id),
        neighbours_(machine.regions_.neighbours(id)),
        sender_(machine.channel_.sender(id)) {
    for (int n : neighbours_) incoming_.push_back(machine.queue(n, id));
    toRing_.assign(neighbours_.size(), false);
  }

  std::size_t trySend(int neighbour, std::span<const Message> messages) override {
    const std::size_t slot = machine_.regions_.neighbourSlot(id_, neighbour);
    const std::size_t sent = machine_.outgoing_[id_][slot]->tryPushN(messages);
    if (sent > 0 && !toRing_[slot]) {
      toRing_[slot] = true;
      pushedTo_.push_back(slot);
    }
    return sent;
  }
  // Wakes the neighbours sent rays since the last call, if they sleep.
  void ringNeighbours() {
    for (std::size_t slot : pushedTo_) {
      machine_.bells_[neighbours_[slot]]->ring();
      toRing_[slot] = false;
    }
    pushedTo_.clear();
  }
  bool canSend(int neighbour) const override { return machine_.queue(id_, neighbour)->hasSpace(); }
  std::size_t receive(std::span<Message> into) override { return inbox_.receive(incoming_, into); }
  bool anyIncoming() const override { return FaceFifoInbox::anyIncoming(incoming_); }

  void sendContribution(const core::Contribution& c) override { sender_.send(c); }
  void flushContributions() override { sender_.flush(); }

  void countWaiting(std::ptrdiff_t change) override { machine_.countWaiting(change); }
  bool primariesHeld() const override { return machine_.primariesHeld(); }
  bool hasToken() const override { return machine_.tokenSlots_[id_]->holds(); }
  bool receiveToken(node::Token& token) override { return machine_.tokenSlots_[id_]->take(token); }
  void passToken(const node::Token& token) override {
    const int next = (id_ + 1) % machine_.regions_.processors();
    machine_.tokenSlots_[next]->put(token);
    machine_.bells_[next]->ring();
  }
  void announceTermination() override { machine_.stop(); }
  bool terminated() const override { return machine_.terminated(); }

 private:
  SharedMemoryInterconnect& machine_;
  int id_;
  const std::vector<int>& neighbours_;  // by slot
  ContributionChannel::Sender sender_;
  std::vector<RayQueue*> incoming_;
  FaceFifoInbox inbox_;
  std::vector<bool> toRing_;           // per neighbour slot: in pushedTo_
  std::vector<std::size_t> pushedTo_;  // the slots of the neighbours sent rays since the last ring
};

template <class Real>
SharedMemoryInterconnect<Real>::SharedMemoryInterconnect(const node::RegionMap& regions,
                                                         std::size_t queueCapacity, std::size_t backlogLimit)
    : regions_(regions),
      backlogLimit_(std::int64_t(backlogLimit)),
      backlogRelease_(std::int64_t(node::scheduling::machineBacklogRelease(backlogLimit))),
      bells_([&] {
        std::vector<std::unique_ptr<Doorbell>> bells;
        // Rung once per step, not per ray (ringNeighbours): the ringer's fence costs little, and a
        // processor going to sleep, which 64 of them on two cores do often, pays no membarrier.
        for (int p = 0; p < regions.processors(); ++p)
          bells.push_back(std::make_unique<Doorbell>(FenceMode::kSymmetric));
        return bells;
      }()),
      fifoSlots_(fifoSlotsOf(regions, queueCapacity)),
      channel_(std::size_t(regions.processors()),
               node::scheduling::contributionBlocksPerProcessor(std::size_t(regions.processors())),
               rawBells(bells_)) {
  // Held from zero waiting rays, no primary ray would ever be shot.
  if (backlogLimit == 0) throw std::invalid_argument("the machine's backlog limit must be at least one ray");
  const int processors = regions.processors();
  outgoing_.resize(std::size_t(processors));
  for (int p = 0; p < processors; ++p) {
    tokenSlots_.push_back(std::make_unique<TokenSlot>());
    // No consumer bell: a FIFO's consumer is woken once per step of its producer (ringNeighbours).
    for (std::size_t k = 0; k < regions.neighbours(p).size(); ++k)
      outgoing_[p].push_back(std::make_unique<RayQueue>(
          SpscOptions{.capacity = queueCapacity, .consumerBell = nullptr, .producerBell = bells_[p].get()},
          fifoSlots_));
  }
  for (int p = 0; p < processors; ++p) endpoints_.push_back(std::make_unique<Endpoint>(*this, p));
}

template <class Real>
SharedMemoryInterconnect<Real>::~SharedMemoryInterconnect() = default;

template <class Real>
void SharedMemoryInterconnect<Real>::stop() {
  terminated_.store(true, std::memory_order_release);
  for (const auto& bell : bells_) bell->ring();
  channel_.doorbell().ring();
}

template <class Real>
node::BasicTransport<Real>& SharedMemoryInterconnect<Real>::endpoint(int processor) {
  return *endpoints_[processor];
}

template <class Real>
void SharedMemoryInterconnect<Real>::ringNeighbours(int processor) {
  endpoints_[processor]->ringNeighbours();
}

template <class Real>
typename SharedMemoryInterconnect<Real>::RayQueue* SharedMemoryInterconnect<Real>::queue(int from,
                                                                                         int to) const {
  return outgoing_[from][regions_.neighbourSlot(from, to)].get();
}

// The count and whether it holds primaries back change together, in one word (count << 1 | held): held
// from backlogLimit_ waiting rays until fewer than backlogRelease_ wait. The change that lets
// go rings every processor: those held back sleep until it does (their readiness reads the word after it is
// published, as a FIFO's after a push).
template <class Real>
void SharedMemoryInterconnect<Real>::countWaiting(std::ptrdiff_t change) {
  std::uint64_t word = backPressure_.load(std::memory_order_relaxed), next = 0;
  bool letGo = false;
  do {
    const std::int64_t count = std::int64_t(word >> 1) + change;
    const bool held = (word & 1) != 0;
    const bool holds = count >= (held ? backlogRelease_ : backlogLimit_);
    letGo = held && !holds;
    next = std::uint64_t(count) << 1 | std::uint64_t(holds);
  } while (
      !backPressure_.compare_exchange_weak(word, next, std::memory_order_acq_rel, std::memory_order_relaxed));
  if (letGo)
    for (const auto& bell : bells_) bell->ring();
}

template <class Real>
bool SharedMemoryInterconnect<Real>::primariesHeld() const {
  return (backPressure_.load(std::memory_order_acquire) & 1) != 0;
}

template <class Real>
QueueStats SharedMemoryInterconnect<Real>::outgoingStats(int processor, node::Face face) const {
  QueueStats sum;
  for (int n : regions_.neighbours(processor))
    if (regions_.faceToward(processor, n) == face) sum += queue(processor, n)->stats();
  return sum;
}

template class SharedMemoryInterconnect<float>;
template class SharedMemoryInterconnect<double>;

}  // namespace raycube::queues
