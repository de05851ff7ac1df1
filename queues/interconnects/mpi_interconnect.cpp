#include "queues/interconnects/mpi_interconnect.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "queues/interconnects/face_fifo_inbox.h"

namespace raycube::queues {
namespace {

using Clock = std::chrono::steady_clock;

// Packet bodies: arrays of these, as bytes (every rank runs the same binary).
template <class Real>
struct WireRay {
  std::uint16_t from = 0, to = 0;  // the directed edge between neighbouring processors it travels on
  node::BasicRayMessage<Real> message;
};
struct WireCredit {
  std::uint16_t from = 0, to = 0;  // the edge whose FIFO has room again
  std::uint32_t count = 0;
};
struct WireToken {
  std::int32_t to = 0;
  node::Token token;
};

template <class T>
void append(std::vector<char>& bytes, const T& value) {
  const char* p = reinterpret_cast<const char*>(&value);
  bytes.insert(bytes.end(), p, p + sizeof value);
}

// The communication task sleeps this long at most when idle (MPI messages arriving ring no bell), and
// much less while rays it sent await their credits or rays it received await their processor.
constexpr auto kLongestNap = std::chrono::microseconds(400);
constexpr auto kShortestNap = std::chrono::microseconds(20);
constexpr int kYieldsIdle = 16, kYieldsInFlight = 256;
constexpr auto kProgressPeriod = std::chrono::milliseconds(100);

}  // namespace

template <class Real>
struct MpiInterconnect<Real>::RemoteOut {
  RemoteOut(int from, int to, int rank, const SpscOptions& options, std::size_t capacity)
      : from(from), to(to), rank(rank), queue(options), credits(std::int64_t(capacity)) {}
  int from, to, rank;
  RayQueue queue;  // the processor's FIFO towards the communication task
  std::atomic<std::int64_t> credits;
};

template <class Real>
struct MpiInterconnect<Real>::RemoteIn {
  RemoteIn(int from, int to, int rank, const SpscOptions& options)
      : from(from), to(to), rank(rank), queue(options) {}
  int from, to, rank;
  RayQueue queue;  // from the communication task to the processor
  std::uint64_t pushed = 0, returned = 0, lastConsumed = 0;
};

template <class Real>
class MpiInterconnect<Real>::Endpoint final : public node::BasicTransport<Real> {
 public:
  Endpoint(MpiInterconnect& net, int id, std::size_t localIndex)
      : net_(net), id_(id), sender_(net.contributions_.sender(localIndex)) {}

  std::size_t trySend(int neighbour, std::span<const Message> messages) override {
    const std::size_t slot = net_.regions_.neighbourSlot(id_, neighbour);
    RayQueue* fifo = net_.outgoing_[id_][slot];
    std::atomic<std::int64_t>* credits = net_.credits_[id_][slot];
    if (credits == nullptr) return fifo->tryPushN(messages);
    const auto room = std::size_t(std::max<std::int64_t>(0, credits->load(std::memory_order_acquire)));
    const std::size_t pushed = fifo->tryPushN(messages.first(std::min(room, messages.size())));
    if (pushed > 0) {
      credits->fetch_sub(std::int64_t(pushed), std::memory_order_acq_rel);
      net_.taskBell_.ring();
    }
    return pushed;
  }
  bool canSend(int neighbour) const override {
    const std::size_t slot = net_.regions_.neighbourSlot(id_, neighbour);
    if (const auto* credits = net_.credits_[id_][slot]) return credits->load(std::memory_order_acquire) > 0;
    return net_.outgoing_[id_][slot]->hasSpace();
  }
  std::size_t receive(std::span<Message> into) override { return inbox_.receive(net_.incoming_[id_], into); }
  bool anyIncoming() const override { return FaceFifoInbox::anyIncoming(net_.incoming_[id_]); }

  void sendContribution(const core::Contribution& c) override { sender_.send(c); }
  void flushContributions() override {
    if (sender_.unsent() == 0) return;
    sender_.flush();
    net_.taskBell_.ring();
  }

  bool hasToken() const override { return net_.tokenSlots_[id_]->holds(); }
  bool receiveToken(node::Token& token) override { return net_.tokenSlots_[id_]->take(token); }
  void passToken(const node::Token& token) override {
    const int next = (id_ + 1) % net_.regions_.processors();
    if (net_.local(next)) return net_.deliverToken(next, token);
    net_.tokenOut_.put(OutgoingToken{next, token});
    net_.taskBell_.ring();
  }
  void announceTermination() override {
    net_.announced_.store(true, std::memory_order_release);
    net_.terminateHere();
    net_.taskBell_.ring();
  }
  bool terminated() const override { return net_.terminated(); }

 private:
  MpiInterconnect& net_;
  int id_;
  HostChannel<core::Contribution, node::scheduling::kContributionBlock>::Sender sender_;
  FaceFifoInbox inbox_;
};

template <class Real>
void MpiInterconnect<Real>::TaskBell::ring() {
  rings_.fetch_add(1);
  if (sleeping_.load()) {
    std::lock_guard lock(mutex_);
    wake_.notify_one();
  }
}

template <class Real>
void MpiInterconnect<Real>::TaskBell::sleepFor(std::chrono::microseconds timeout) {
  std::unique_lock lock(mutex_);
  const std::uint64_t seen = rings_.load();
  sleeping_.store(true);
  wake_.wait_for(lock, timeout, [&] { return rings_.load() != seen; });
  sleeping_.store(false);
}

namespace {

std::vector<int> processorsOfRank(const std::vector<int>& rankOf, int rank) {
  std::vector<int> ids;
  for (int p = 0; p < int(rankOf.size()); ++p)
    if (rankOf[p] == rank) ids.push_back(p);
  return ids;
}

}  // namespace

template <class Real>
MpiInterconnect<Real>::MpiInterconnect(const node::RegionMap& regions, MpiWiring wiring, MpiLink& link)
    : regions_(regions),
      wiring_(std::move(wiring)),
      link_(link),
      creditBatch_(
          std::clamp<std::size_t>(wiring_.capacity / 2, 1, std::max<std::size_t>(1, wiring_.rayBatch))),
      bells_(std::size_t(regions.processors())),
      tokenSlots_(std::size_t(regions.processors())),
      outgoing_(std::size_t(regions.processors())),
      credits_(std::size_t(regions.processors())),
      incoming_(std::size_t(regions.processors())),
      batches_(std::size_t(link.size())),
      batchRays_(std::size_t(link.size()), 0),
      scratch_(wiring_.rayBatch),
      creditPackets_(std::size_t(link.size())),
      localIds_(processorsOfRank(wiring_.rankOf, link.rank())),
      contributions_(localIds_.size(), node::scheduling::contributionBlocksPerProcessor(localIds_.size()),
                     [&] {
                       std::vector<Doorbell*> bells;
                       for (int p : localIds_)
                         bells.push_back((bells_[p] = std::make_unique<Doorbell>()).get());
                       return bells;
                     }()) {
  if (int(wiring_.rankOf.size()) != regions.processors())
    throw std::invalid_argument("MpiInterconnect: a rank for every processor");
  std::map<std::pair<int, int>, RayQueue*> localFifo;
  for (int p : localIds_) {
    tokenSlots_[p] = std::make_unique<TokenSlot>();
    for (int n : regions.neighbours(p))
      if (local(n)) {
        localFifos_.push_back(std::make_unique<RayQueue>(SpscOptions{
            .capacity = wiring_.capacity, .consumerBell = bells_[n].get(), .producerBell = bells_[p].get()}));
        localFifo[{p, n}] = localFifos_.back().get();
      }
  }
  for (int p : localIds_) {
    for (int n : regions.neighbours(p)) {
      if (local(n)) {
        outgoing_[p].push_back(localFifo.at({p, n}));
        credits_[p].push_back(nullptr);
        incoming_[p].push_back(localFifo.at({n, p}));
        continue;
      }
      const int rank = wiring_.rankOf[n];
      remoteOut_.push_back(std::make_unique<RemoteOut>(
          p, n, rank, SpscOptions{.capacity = wiring_.capacity, .producerBell = bells_[p].get()},
          wiring_.capacity));
      remoteOutByEdge_[{p, n}] = remoteOut_.back().get();
      outgoing_[p].push_back(&remoteOut_.back()->queue);
      credits_[p].push_back(&remoteOut_.back()->credits);
      auto in = std::make_unique<RemoteIn>(
          n, p, rank, SpscOptions{.capacity = wiring_.capacity, .consumerBell = bells_[p].get()});
      incoming_[p].push_back(&in->queue);
      remoteIn_[{n, p}] = std::move(in);
    }
  }
  endpoints_.resize(std::size_t(regions.processors()));
  for (std::size_t k = 0; k < localIds_.size(); ++k)
    endpoints_[localIds_[k]] = std::make_unique<Endpoint>(*this, localIds_[k], k);
}

template <class Real>
MpiInterconnect<Real>::~MpiInterconnect() = default;

template <class Real>
node::BasicTransport<Real>& MpiInterconnect<Real>::endpoint(int processor) {
  if (!local(processor)) throw std::logic_error("MpiInterconnect: processor of another rank");
  return *endpoints_[processor];
}

template <class Real>
QueueStats MpiInterconnect<Real>::outgoingStats(int processor, node::Face face) const {
  QueueStats sum;
  const std::vector<int>& neighbours = regions_.neighbours(processor);
  for (std::size_t k = 0; k < neighbours.size(); ++k)
    if (regions_.faceToward(processor, neighbours[k]) == face) sum += outgoing_[processor][k]->stats();
  return sum;
}

template <class Real>
void MpiInterconnect<Real>::deliverToken(int to, const node::Token& token) {
  tokenSlots_[to]->put(token);
  bells_[to]->ring();
}

template <class Real>
void MpiInterconnect<Real>::terminateHere() {
  terminated_.store(true, std::memory_order_release);
  for (int p : localIds_) bells_[p]->ring();
}

template <class Real>
void MpiInterconnect<Real>::onPacket(int from, Packet kind, std::span<const char> bytes,
                                     const ServeHooks& hooks) {
  switch (kind) {
    case Packet::Rays: {
      RemoteIn* in = nullptr;  // a batch's rays mostly share their edge: look it up when it changes
      return forEachEntry<WireRay<Real>>(bytes, [&](const WireRay<Real>& r) {
        if (in == nullptr || in->from != r.from || in->to != r.to) in = remoteIn_.at({r.from, r.to}).get();
        if (!in->queue.tryPush(r.message))
          throw std::logic_error("a rank sent more rays than the FIFO's credits allow");
        ++in->pushed;
      });
    }
    case Packet::Credits:
      return forEachEntry<WireCredit>(bytes, [&](const WireCredit& c) {
        remoteOutByEdge_.at({c.from, c.to})->credits.fetch_add(c.count, std::memory_order_acq_rel);
        bells_[c.from]->ring();
      });
    case Packet::Token:
      return forEachEntry<WireToken>(bytes, [&](const WireToken& t) { deliverToken(t.to, t.token); });
    case Packet::Terminate:
      return terminateHere();
    default:
      if (hooks.other) hooks.other(from, kind, bytes);
  }
}

// Rays the processors handed over, into each destination rank's batch; full batches leave at once.
template <class Real>
bool MpiInterconnect<Real>::collectRays(bool& anyGrew, std::vector<char>& grew) {
  for (const auto& out : remoteOut_) {
    for (;;) {
      const std::size_t room = wiring_.rayBatch - std::size_t(batchRays_[out->rank]);
      const std::size_t n = out->queue.tryPopN(std::span<Message>(scratch_.data(), room));
      if (n == 0) break;
      std::vector<char>& batch = batches_[out->rank];
      if (batch.empty()) batch.reserve(wiring_.rayBatch * sizeof(WireRay<Real>));
      for (std::size_t k = 0; k < n; ++k)
        append(batch, WireRay<Real>{std::uint16_t(out->from), std::uint16_t(out->to), scratch_[k]});
      batchRays_[out->rank] += int(n);
      grew[out->rank] = 1;
      anyGrew = true;
      if (std::size_t(batchRays_[out->rank]) == wiring_.rayBatch) sendRays(out->rank);
    }
  }
  return anyGrew;
}

template <class Real>
void MpiInterconnect<Real>::sendRays(int rank) {
  ++rayTraffic_.rayMessages;
  rayTraffic_.raysSent += std::uint64_t(batchRays_[rank]);
  link_.post(rank, Packet::Rays, std::move(batches_[rank]));
  batches_[rank] = {};
  batchRays_[rank] = 0;
}

// Room the local processors made by taking rays from other ranks: credits go back in batches, or at once
// when the processor has stopped taking (so a FIFO of capacity 1 still moves).
template <class Real>
bool MpiInterconnect<Real>::returnCredits(bool flushAll) {
  std::vector<std::vector<char>>& packets = creditPackets_;  // per rank
  bool any = false;
  for (auto& [edge, in] : remoteIn_) {
    const std::uint64_t consumed = in->pushed - in->queue.size();
    const std::uint64_t pending = consumed - in->returned;
    const bool quiet = consumed == in->lastConsumed;
    in->lastConsumed = consumed;
    if (pending == 0 || !(flushAll || quiet || pending >= creditBatch_)) continue;
    append(packets[in->rank],
           WireCredit{std::uint16_t(in->from), std::uint16_t(in->to), std::uint32_t(pending)});
    in->returned = consumed;
  }
  for (std::size_t rank = 0; rank < packets.size(); ++rank) {
    if (packets[rank].empty()) continue;
    link_.post(int(rank), Packet::Credits, std::move(packets[rank]));
    packets[rank] = {};
    any = true;
  }
  return any;
}

template <class Real>
bool MpiInterconnect<Real>::forwardToken() {
  OutgoingToken out;
  if (!tokenOut_.take(out)) return false;
  link_.postValue(wiring_.rankOf[out.to], Packet::Token, WireToken{out.to, out.token});
  return true;
}

// Contribution blocks of the local processors, to the host in packets of up to kContributionsPerShipment.
template <class Real>
bool MpiInterconnect<Real>::forwardContributions(bool flush) {
  const std::size_t n =
      contributions_.drain([&](const core::Contribution& c) { contributionBlock_.push_back(c); });
  if (!contributionBlock_.empty() &&
      (flush || n == 0 || contributionBlock_.size() >= kContributionsPerShipment)) {
    const char* p = reinterpret_cast<const char*>(contributionBlock_.data());
    link_.post(0, Packet::Contributions,
               std::vector<char>(p, p + contributionBlock_.size() * sizeof(core::Contribution)));
    contributionBlock_.clear();
  }
  return n > 0;
}

template <class Real>
void MpiInterconnect<Real>::serve(const ServeHooks& hooks) {
  const MpiLink::OnPacket handle = [&](int from, Packet kind, std::span<const char> bytes) {
    onPacket(from, kind, bytes, hooks);
  };
  std::vector<char> grew(std::size_t(link_.size()));
  auto nextProgress = Clock::now() + kProgressPeriod;
  std::vector<ProcessorProgress> reported;
  int idlePasses = 0;
  auto lastWork = Clock::now();
  bool described = false;
  for (;;) {
    bool worked = link_.poll(handle) > 0;
    bool anyGrew = false;
    std::fill(grew.begin(), grew.end(), 0);
    worked |= collectRays(anyGrew, grew);
    // A batch that did not grow during this pass leaves now, full or not.
    for (int r = 0; r < link_.size(); ++r)
      if (batchRays_[r] > 0 && !grew[r]) {
        sendRays(r);
        worked = true;
      }
    worked |= returnCredits(false);
    worked |= forwardToken();
    worked |= forwardContributions(false);
    worked |= announceTermination();
    link_.progressSends();
    if (hooks.check) hooks.check();
    // Processor 0 may announce between the line above and this one: the announcement still leaves below.
    if (terminated() && hooks.stopped()) break;
    reportProgress(hooks, nextProgress, reported);
    if (worked) {
      idlePasses = 0;
      lastWork = Clock::now();
      continue;
    }
    if (!described && Clock::now() - lastWork > std::chrono::seconds(10) &&
        std::getenv("RAYCUBE_MPI_DEBUG")) {
      std::fprintf(stderr, "%s\n", describe().c_str());
      described = true;
    }
    waitIdle(++idlePasses);
  }
  announceTermination();
  forwardContributions(true);
}

template <class Real>
void MpiInterconnect<Real>::reportProgress(const ServeHooks& hooks, Clock::time_point& next,
                                           std::vector<ProcessorProgress>& reported) {
  if (Clock::now() < next) return;
  next = Clock::now() + kProgressPeriod;
  if (std::vector<ProcessorProgress> now = hooks.progress(); now != reported) {
    const char* bytes = reinterpret_cast<const char*>(now.data());
    link_.post(0, Packet::Progress, std::vector<char>(bytes, bytes + now.size() * sizeof now[0]));
    reported = std::move(now);
  }
}

template <class Real>
void MpiInterconnect<Real>::waitIdle(int idlePasses) {
  // Rays in flight either way: credits or rays will arrive soon, and nothing rings for them, so the task
  // yields longer before it naps, and naps shorter.
  const bool inFlight = raysInFlight();
  const int yields = inFlight ? kYieldsInFlight : kYieldsIdle;
  if (idlePasses < yields) {
    std::this_thread::yield();
  } else {
    taskBell_.sleepFor(std::min<std::chrono::microseconds>(
        inFlight ? kShortestNap : kLongestNap,
        std::chrono::microseconds(10 << std::min(idlePasses - yields, 6))));
  }
}

template <class Real>
std::string MpiInterconnect<Real>::describe() const {
  std::string text = "rank " + std::to_string(link_.rank()) + (terminated() ? " (terminated)" : "") + ":";
  for (const auto& out : remoteOut_)
    text += " out " + std::to_string(out->from) + "->" + std::to_string(out->to) + " credits " +
            std::to_string(out->credits.load()) + " queued " + std::to_string(out->queue.size()) + ";";
  for (const auto& [edge, in] : remoteIn_)
    text += " in " + std::to_string(in->from) + "->" + std::to_string(in->to) + " pushed " +
            std::to_string(in->pushed) + " waiting " + std::to_string(in->queue.size()) + " returned " +
            std::to_string(in->returned) + ";";
  for (int r = 0; r < link_.size(); ++r)
    if (batchRays_[r] > 0)
      text += " batch for rank " + std::to_string(r) + ": " + std::to_string(batchRays_[r]) + ";";
  return text;
}

template <class Real>
std::size_t MpiInterconnect<Real>::raysToward(int from, int to) const {
  const std::size_t slot = regions_.neighbourSlot(from, to);
  if (const auto* credits = credits_[from][slot])
    return std::size_t(std::max<std::int64_t>(0, std::int64_t(wiring_.capacity) - credits->load()));
  return outgoing_[from][slot]->size();
}

template <class Real>
bool MpiInterconnect<Real>::raysInFlight() const {
  for (const auto& out : remoteOut_)
    if (out->credits.load(std::memory_order_relaxed) < std::int64_t(wiring_.capacity)) return true;
  for (const auto& [edge, in] : remoteIn_)
    if (in->pushed != in->returned) return true;
  return false;
}

// Processor 0 proved termination here: every other rank of processors learns it.
template <class Real>
bool MpiInterconnect<Real>::announceTermination() {
  if (!announced_.exchange(false)) return false;
  for (int r = 1; r < link_.size(); ++r)
    if (r != link_.rank()) link_.post(r, Packet::Terminate, {});
  return true;
}

template class MpiInterconnect<float>;
template class MpiInterconnect<double>;

}  // namespace raycube::queues
