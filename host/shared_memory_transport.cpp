#include "host/shared_memory_transport.h"

#include "queues/wait.h"

namespace raycube::host {
namespace {

std::vector<queues::Doorbell*> rawBells(const std::vector<std::unique_ptr<queues::Doorbell>>& bells) {
  std::vector<queues::Doorbell*> raw;
  for (const auto& b : bells) raw.push_back(b.get());
  return raw;
}

}  // namespace

class SharedMemoryMachine::Endpoint final : public node::Transport {
 public:
  Endpoint(SharedMemoryMachine& machine, int id) : machine_(machine), id_(id), sender_(machine.channel_.sender(id)) {
    for (int f = 0; f < node::kFaces; ++f) {
      outgoing_[f] = machine.queues_[std::size_t(id) * node::kFaces + f].get();
      const int n = machine.regions_.neighbour(id, node::Face(f));
      incoming_[f] = n < 0 ? nullptr
                           : machine.queues_[std::size_t(n) * node::kFaces + int(node::opposite(node::Face(f)))].get();
    }
  }

  bool hasNeighbour(node::Face face) const override { return outgoing_[int(face)] != nullptr; }
  std::size_t trySend(node::Face face, std::span<const node::RayMessage> messages) override {
    return outgoing_[int(face)]->tryPushN(messages);
  }
  bool canSend(node::Face face) const override { return outgoing_[int(face)]->hasSpace(); }
  std::size_t receive(std::span<node::RayMessage> into) override {
    std::size_t n = 0;
    for (int k = 0; k < node::kFaces && n < into.size(); ++k) {
      RayQueue* q = incoming_[(next_ + k) % node::kFaces];
      if (q != nullptr) n += q->tryPopN(into.subspan(n));
    }
    next_ = (next_ + 1) % node::kFaces;  // fairness between faces
    return n;
  }
  bool anyIncoming() const override {
    for (RayQueue* q : incoming_)
      if (q != nullptr && q->hasMessage()) return true;
    return false;
  }

  void sendContribution(const core::Contribution& c) override { sender_.send(c); }
  void flushContributions() override { sender_.flush(); }

  bool hasToken() const override { return machine_.mailboxes_[id_]->full.load(std::memory_order_acquire); }
  bool receiveToken(node::Token& token) override {
    Mailbox& box = *machine_.mailboxes_[id_];
    if (!box.full.load(std::memory_order_acquire)) return false;
    token = box.token;
    box.full.store(false, std::memory_order_release);
    return true;
  }
  void passToken(const node::Token& token) override {
    const int next = (id_ + 1) % machine_.regions_.processors();
    Mailbox& box = *machine_.mailboxes_[next];
    box.token = token;  // only one token exists: the mailbox is empty here
    box.full.store(true, std::memory_order_release);
    machine_.bells_[next]->ring();
  }
  void announceTermination() override {
    machine_.terminated_.store(true, std::memory_order_release);
    for (const auto& bell : machine_.bells_) bell->ring();
    machine_.channel_.doorbell().ring();
  }
  bool terminated() const override { return machine_.terminated(); }
  void waitUntil(const std::function<bool()>& ready) override { queues::waitUntil(*machine_.bells_[id_], ready, queues::WaitPolicy{4, 8}); }

 private:
  SharedMemoryMachine& machine_;
  int id_;
  ContributionChannel::Sender sender_;
  RayQueue* outgoing_[node::kFaces] = {};
  RayQueue* incoming_[node::kFaces] = {};
  int next_ = 0;
};

SharedMemoryMachine::SharedMemoryMachine(const node::RegionMap& regions, std::size_t queueCapacity)
    : regions_(regions),
      bells_([&] {
        std::vector<std::unique_ptr<queues::Doorbell>> bells;
        for (int p = 0; p < regions.processors(); ++p) bells.push_back(std::make_unique<queues::Doorbell>());
        return bells;
      }()),
      channel_(std::size_t(regions.processors()), kContributionBlocksPerProcessor, rawBells(bells_)) {
  const int processors = regions.processors();
  queues_.resize(std::size_t(processors) * node::kFaces);
  for (int p = 0; p < processors; ++p) {
    mailboxes_.push_back(std::make_unique<Mailbox>());
    for (int f = 0; f < node::kFaces; ++f) {
      const int n = regions.neighbour(p, node::Face(f));
      if (n < 0) continue;
      queues_[std::size_t(p) * node::kFaces + f] = std::make_unique<RayQueue>(queues::SpscOptions{
          .capacity = queueCapacity, .consumerBell = bells_[n].get(), .producerBell = bells_[p].get()});
    }
  }
  for (int p = 0; p < processors; ++p) endpoints_.push_back(std::make_unique<Endpoint>(*this, p));
}

SharedMemoryMachine::~SharedMemoryMachine() = default;

node::Transport& SharedMemoryMachine::endpoint(int processor) { return *endpoints_[processor]; }

queues::QueueStats SharedMemoryMachine::outgoingStats(int processor, node::Face face) const {
  const auto& q = queues_[std::size_t(processor) * node::kFaces + int(face)];
  return q ? q->stats() : queues::QueueStats{};
}

}  // namespace raycube::host
