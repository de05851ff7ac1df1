#include "queues/interconnects/simgrid_interconnect.h"

#include <algorithm>
#include <cstdint>

#include "node/scheduling.h"

namespace raycube::queues {

namespace s4u = simgrid::s4u;

template <class Real>
struct SimGridInterconnect<Real>::Packet {
  enum class Kind : std::uint8_t { Ray, Token, Contributions, Finished };
  Kind kind = Kind::Ray;
  int from = 0;
  int to = -1;  // a processor, or -1: the host
  Message ray{};
  node::Token token{};
  std::vector<core::Contribution> contributions;
  std::uint64_t contributionsSent = 0;  // Finished: how many the host must have received from `from`

  // What travels on the wire: the paper's rayon, the token, a block of contributions.
  double bytes() const {
    switch (kind) {
      case Kind::Ray:
        return sizeof(Message);
      case Kind::Token:
        return sizeof(node::Token);
      case Kind::Contributions:
        return double(contributions.size() * sizeof(core::Contribution));
      case Kind::Finished:
        return sizeof(std::uint64_t);
    }
    return 0;
  }
};

template <class Real>
class SimGridInterconnect<Real>::Endpoint final : public node::BasicTransport<Real> {
 public:
  Endpoint(SimGridInterconnect& net, int id)
      : net_(net), id_(id), creditsUsed_(net.regions_.neighbours(id).size(), 0) {}

  std::size_t trySend(int neighbour, std::span<const Message> messages) override {
    std::size_t& used = creditsUsed_[slotOf(neighbour)];
    const std::size_t n = std::min(messages.size(), net_.wiring_.capacity - used);
    used += n;
    for (std::size_t k = 0; k < n; ++k) {
      auto p = std::make_unique<Packet>();
      p->kind = Packet::Kind::Ray;
      p->from = id_;
      p->to = neighbour;
      p->ray = messages[k];
      outbox_.push_back(std::move(p));
    }
    return n;
  }
  std::size_t receive(std::span<Message> into) override {
    std::size_t n = 0;
    for (; n < into.size() && !inbox_.empty(); ++n) {
      const auto [from, message] = inbox_.front();
      inbox_.pop_front();
      into[n] = message;
      net_.endpoints_[from]->returnCredit(id_);  // the ray has left the FIFO: its slot is free again
    }
    return n;
  }
  bool anyIncoming() const override { return !inbox_.empty(); }
  bool canSend(int neighbour) const override {
    return creditsUsed_[slotOf(neighbour)] < net_.wiring_.capacity;
  }

  void sendContribution(const core::Contribution& c) override {
    block_.push_back(c);
    if (block_.size() == node::scheduling::kContributionBlock) flushContributions();
  }
  void flushContributions() override {
    if (block_.empty()) return;
    auto p = std::make_unique<Packet>();
    p->kind = Packet::Kind::Contributions;
    p->from = id_;
    contributionsSent_ += block_.size();
    p->contributions = std::move(block_);
    block_.clear();
    outbox_.push_back(std::move(p));
  }

  bool hasToken() const override { return token_.has_value(); }
  bool receiveToken(node::Token& token) override {
    if (!token_) return false;
    token = *token_;
    token_.reset();
    return true;
  }
  void passToken(const node::Token& token) override {
    auto p = std::make_unique<Packet>();
    p->kind = Packet::Kind::Token;
    p->from = id_;
    p->to = (id_ + 1) % net_.regions_.processors();
    p->token = token;
    outbox_.push_back(std::move(p));
  }
  // The host broadcasts the end (3.6); a broadcast costs little beside the run, so it is instant here.
  void announceTermination() override {
    net_.terminated_ = true;
    for (int p = 0; p < net_.regions_.processors(); ++p) net_.wake(p);
  }
  bool terminated() const override { return net_.terminated_; }

  // ---- The interconnect's side.
  void returnCredit(int neighbour) {
    --creditsUsed_[slotOf(neighbour)];
    net_.wake(id_);
  }
  void arrive(int from, const Message& m) { inbox_.emplace_back(from, m); }
  void arrive(const node::Token& t) { token_ = t; }
  std::vector<std::unique_ptr<Packet>> takeOutbox() { return std::exchange(outbox_, {}); }
  std::uint64_t contributionsSent() const { return contributionsSent_; }
  std::size_t creditsUsed(int neighbour) const { return creditsUsed_[slotOf(neighbour)]; }

 private:
  std::size_t slotOf(int neighbour) const { return net_.regions_.neighbourSlot(id_, neighbour); }

  SimGridInterconnect& net_;
  int id_;
  std::vector<std::size_t> creditsUsed_;  // per neighbour: rays sent and not yet taken in
  std::deque<std::pair<int, Message>> inbox_;
  std::optional<node::Token> token_;
  std::vector<std::unique_ptr<Packet>> outbox_;  // produced by the current step
  std::vector<core::Contribution> block_;
  std::uint64_t contributionsSent_ = 0;
};

template <class Real>
SimGridInterconnect<Real>::SimGridInterconnect(const node::RegionMap& regions, SimGridWiring wiring)
    : regions_(regions),
      wiring_(std::move(wiring)),
      processorAt_(wiring_.hosts.size(), -1),
      mutex_(s4u::Mutex::create()),
      relaySeconds_(wiring_.hosts.size(), 0.0),
      relayed_(wiring_.hosts.size(), 0),
      lastRelay_(wiring_.hosts.size(), SIZE_MAX) {
  for (int p = 0; p < regions.processors(); ++p) {
    processorAt_.at(wiring_.cubeNode.at(p)) = p;
    endpoints_.push_back(std::make_unique<Endpoint>(*this, p));
    wakeUp_.push_back(s4u::ConditionVariable::create());
  }
}

template <class Real>
SimGridInterconnect<Real>::~SimGridInterconnect() = default;

template <class Real>
node::BasicTransport<Real>& SimGridInterconnect<Real>::endpoint(int processor) {
  return *endpoints_[processor];
}

template <class Real>
void SimGridInterconnect<Real>::startCommunicationTasks() {
  for (std::uint32_t n = 0; n < wiring_.hosts.size(); ++n)
    s4u::Actor::create("communication-" + std::to_string(n), wiring_.hosts[n], [this, n] {
      communicationTask(n);
    })->daemonize();
}

template <class Real>
void SimGridInterconnect<Real>::commit(int processor) {
  for (auto& packet : endpoints_[processor]->takeOutbox())
    route(wiring_.cubeNode[processor], std::move(packet));
}

template <class Real>
void SimGridInterconnect<Real>::finish(int processor) {
  auto p = std::make_unique<Packet>();
  p->kind = Packet::Kind::Finished;
  p->from = processor;
  p->contributionsSent = endpoints_[processor]->contributionsSent();
  route(wiring_.cubeNode[processor], std::move(p));
}

// The next hop of a packet at hypercube node `at`: the host directly (its own link, as the iPSC's eighth
// port), the node itself, or a neighbour on the e-cube path (store and forward) or the destination.
template <class Real>
void SimGridInterconnect<Real>::route(std::uint32_t at, std::unique_ptr<Packet> packet) {
  const double bytes = packet->bytes();
  if (packet->to < 0) {
    LinkTrafficCount& t = traffic_[{at, -1}];
    ++t.messages;
    t.bytes += std::uint64_t(bytes);
    s4u::Mailbox::by_name(kCubeManagerHost)->put_init(packet.release(), bytes)->detach();
    return;
  }
  const std::uint32_t target = wiring_.cubeNode[packet->to];
  if (target == at) return deliver(std::move(packet));
  const std::uint32_t next = wiring_.routing == Routing::StoreAndForward ? ecubeNextHop(at, target) : target;
  LinkTrafficCount& t = traffic_[{at, next}];
  ++t.messages;
  t.bytes += std::uint64_t(bytes);
  s4u::Mailbox::by_name("cube-" + std::to_string(next))->put_init(packet.release(), bytes)->detach();
}

template <class Real>
void SimGridInterconnect<Real>::communicationTask(std::uint32_t cubeNode) {
  s4u::Mailbox* mailbox = s4u::Mailbox::by_name("cube-" + std::to_string(cubeNode));
  // A permanent receiver: a packet starts crossing the links when it is sent, not when this task gets to
  // it (SimGrid starts a transfer when a get matches it); otherwise one packet at a time pays the latency.
  mailbox->set_receiver(s4u::Actor::self());
  for (;;) {
    std::unique_ptr<Packet> packet(mailbox->get<Packet>());
    if (wiring_.cubeNode[packet->to] == cubeNode) {
      deliver(std::move(packet));
      continue;
    }
    const double start = s4u::Engine::get_clock();
    // Store and forward, on this node's CPU: seconds at its host's speed.
    s4u::this_actor::execute(wiring_.relaySeconds * s4u::this_actor::get_host()->get_speed());
    const double end = s4u::Engine::get_clock();
    relaySeconds_[cubeNode] += end - start;
    std::size_t& last = lastRelay_[cubeNode];
    if (last != SIZE_MAX && relayIntervals_[last].end == start) {
      relayIntervals_[last].end = end;
    } else {
      last = relayIntervals_.size();
      relayIntervals_.push_back({cubeNode, start, end});
    }
    ++relayed_[cubeNode];
    route(cubeNode, std::move(packet));
  }
}

template <class Real>
void SimGridInterconnect<Real>::deliver(std::unique_ptr<Packet> packet) {
  Endpoint& to = *endpoints_[packet->to];
  if (packet->kind == Packet::Kind::Ray)
    to.arrive(packet->from, packet->ray);
  else
    to.arrive(packet->token);
  wake(packet->to);
}

template <class Real>
void SimGridInterconnect<Real>::serveHost(core::ContributionSink& sink) {
  s4u::Mailbox* mailbox = s4u::Mailbox::by_name(kCubeManagerHost);
  mailbox->set_receiver(s4u::Actor::self());  // as communicationTask: packets cross while others arrive
  std::uint64_t expected = 0, received = 0;
  for (int finished = 0; finished < regions_.processors() || received < expected;) {
    std::unique_ptr<Packet> packet(mailbox->get<Packet>());
    if (packet->kind == Packet::Kind::Finished) {
      ++finished;
      expected += packet->contributionsSent;
      continue;
    }
    for (const core::Contribution& c : packet->contributions) sink.add(c);
    received += packet->contributions.size();
  }
}

template <class Real>
std::size_t SimGridInterconnect<Real>::raysIn(int from, int to) const {
  return endpoints_[from]->creditsUsed(to);
}

template <class Real>
std::vector<LinkTrafficCount> SimGridInterconnect<Real>::traffic() const {
  std::vector<LinkTrafficCount> out;
  for (const auto& [link, t] : traffic_) {
    LinkTrafficCount row = t;
    row.from = std::uint32_t(link.first);
    row.to = std::uint32_t(link.second);
    out.push_back(row);
  }
  return out;
}

template class SimGridInterconnect<float>;
template class SimGridInterconnect<double>;

}  // namespace raycube::queues
