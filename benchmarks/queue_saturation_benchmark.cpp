// Queue saturation microbenchmarks: what the emulated interconnect costs, and how a FIFO saturates when
// its consumer is slower than its producer (Priol & Bouatouch 3.7: 75% of processes locked on full FIFOs).
//
//   queue_saturation_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Throughput/*      producer and consumer pinned to different cores, busy-polling tryPush/tryPop.
// Saturation/*      the consumer does `ratio` times the producer's work per message; blocked_frac is the
//                   share of the producer's time spent blocked on a full queue.
// Oversubscribed/*  N producer/consumer pairs on 2 cores with blocking (sleeping) waits.
// HostChannel/*     64 nodes shipping pixel contributions to one host.
#include <benchmark/benchmark.h>
#include <oneapi/tbb/concurrent_queue.h>
#include <pthread.h>
#include <sched.h>

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <ctime>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "node/ray_message.h"
#include "queues/host_channel.h"
#include "queues/spsc_queue.h"
#include "queues/wait.h"

namespace raycube::queues {
namespace {

struct SmallMessage {
  std::uint64_t value = 0;
};

// The messages the machine's FIFOs carry (queues/interconnects/shared_memory_interconnect.h): a ray in
// double (128 bytes) or float (80 bytes). The sequence number rides in the ray's sample index.
using DoubleRay = node::BasicRayMessage<double>;
using FloatRay = node::BasicRayMessage<float>;
static_assert(sizeof(DoubleRay) == 128 && sizeof(FloatRay) == 80);

template <class T>
T makeMessage(std::uint64_t i) {
  T m{};
  if constexpr (std::is_same_v<T, SmallMessage>)
    m.value = i;
  else
    m.ray.sample = static_cast<std::uint32_t>(i);
  return m;
}

template <class T>
std::uint64_t sequenceOf(const T& m) {
  if constexpr (std::is_same_v<T, SmallMessage>)
    return m.value;
  else
    return m.ray.sample;
}

// ---- The queues under test, behind one interface: tryPush/tryPop (polling) and push/pop (blocking).

// raycube's ring with or without doorbells and accounting; the machine's FIFO has both
// (queues/interconnects/shared_memory_interconnect.h).
template <class T, Accounting kAccounting, bool kBells>
class Raycube {
 public:
  explicit Raycube(std::size_t capacity)
      : queue_({.capacity = capacity,
                .consumerBell = kBells ? &consumerBell_ : nullptr,
                .producerBell = kBells ? &producerBell_ : nullptr}) {}
  bool tryPush(const T& m) { return queue_.tryPush(m); }
  bool tryPop(T& m) { return queue_.tryPop(m); }
  std::size_t tryPushN(std::span<const T> m) { return queue_.tryPushN(m); }
  std::size_t tryPopN(std::span<T> out) { return queue_.tryPopN(out); }
  void push(const T& m) { queue_.push(m); }
  T pop() { return queue_.pop(); }

 private:
  Doorbell consumerBell_, producerBell_;
  SpscQueue<T, kAccounting> queue_;
};

// The bare ring: what busy-polling costs when nobody ever sleeps.
template <class T>
using RaycubeBare = Raycube<T, Accounting::kOff, false>;
template <class T>
using RaycubeBells = Raycube<T, Accounting::kOff, true>;
// The machine's FIFO: doorbells and saturation accounting.
template <class T>
using RaycubeMachine = Raycube<T, Accounting::kOn, true>;

template <class T>
class Tbb {
 public:
  explicit Tbb(std::size_t capacity) { queue_.set_capacity(static_cast<std::ptrdiff_t>(capacity)); }
  bool tryPush(const T& m) { return queue_.try_push(m); }
  bool tryPop(T& m) { return queue_.try_pop(m); }
  void push(const T& m) { queue_.push(m); }
  T pop() {
    T m;
    queue_.pop(m);
    return m;
  }

 private:
  tbb::concurrent_bounded_queue<T> queue_;
};

// The textbook bounded queue: a ring under a mutex, two condition variables.
template <class T>
class MutexCv {
 public:
  explicit MutexCv(std::size_t capacity) : slots_(capacity) {}
  bool tryPush(const T& m) {
    std::lock_guard lock(mutex_);
    if (count_ == slots_.size()) return false;
    put(m);
    return true;
  }
  bool tryPop(T& m) {
    std::lock_guard lock(mutex_);
    if (count_ == 0) return false;
    m = take();
    return true;
  }
  void push(const T& m) {
    std::unique_lock lock(mutex_);
    notFull_.wait(lock, [&] { return count_ < slots_.size(); });
    put(m);
  }
  T pop() {
    std::unique_lock lock(mutex_);
    notEmpty_.wait(lock, [&] { return count_ > 0; });
    return take();
  }

 private:
  void put(const T& m) {
    slots_[(head_ + count_++) % slots_.size()] = m;
    notEmpty_.notify_one();
  }
  T take() {
    const T m = slots_[head_];
    head_ = (head_ + 1) % slots_.size();
    --count_;
    notFull_.notify_one();
    return m;
  }
  std::mutex mutex_;
  std::condition_variable notFull_, notEmpty_;
  std::vector<T> slots_;
  std::size_t head_ = 0, count_ = 0;
};

// ---- Helpers.

void pinTo(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
}

void unpin() {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (unsigned cpu = 0; cpu < std::thread::hardware_concurrency(); ++cpu) CPU_SET(cpu, &set);
  pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
}

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// One unit of simulated work (a dependent multiply-add): the stand-in for tracing a ray.
inline void work(int units) {
  std::uint64_t x = 1;
  for (int i = 0; i < units; ++i) {
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    benchmark::DoNotOptimize(x);
  }
}

void setMessageCounters(benchmark::State& state, std::uint64_t messages, std::size_t messageBytes) {
  state.SetItemsProcessed(static_cast<std::int64_t>(messages));
  state.SetBytesProcessed(static_cast<std::int64_t>(messages * messageBytes));
}

// ---- Throughput: one producer, one consumer, on different cores.

// Busy-polls, but yields after a while so that a partner descheduled by another process can run.
class Poll {
 public:
  void operator()() {
    if (++misses_ < 1024) {
      cpuRelax();
    } else {
      misses_ = 0;
      std::this_thread::yield();
    }
  }

 private:
  int misses_ = 0;
};

std::uint64_t messagesFor(std::size_t capacity) {
  return capacity < 64 ? 1 << 16 : 1 << 20;
}

template <template <class> class Queue, class T>
void Throughput(benchmark::State& state) {
  const auto capacity = static_cast<std::size_t>(state.range(0));
  const std::uint64_t messages = messagesFor(capacity);
  pinTo(0);
  for (auto _ : state) {
    Queue<T> queue(capacity);
    std::uint64_t sum = 0;
    std::thread consumer([&] {
      pinTo(1);
      T m;
      Poll poll;
      for (std::uint64_t i = 0; i < messages; ++i) {
        while (!queue.tryPop(m)) poll();
        sum += sequenceOf(m);
      }
    });
    Poll poll;
    for (std::uint64_t i = 0; i < messages; ++i) {
      const T m = makeMessage<T>(i);
      while (!queue.tryPush(m)) poll();
    }
    consumer.join();
    if (sum != messages * (messages - 1) / 2) state.SkipWithError("lost or duplicated messages");
  }
  unpin();
  setMessageCounters(state, messages * state.iterations(), sizeof(T));
}

// The node's way of moving rays: tryPushN/tryPopN by blocks of 16, one synchronisation per block.
template <template <class> class Queue, class T>
void ThroughputBatched(benchmark::State& state) {
  const auto capacity = static_cast<std::size_t>(state.range(0));
  const std::uint64_t messages = messagesFor(capacity);
  constexpr std::size_t kBatch = 16;
  pinTo(0);
  for (auto _ : state) {
    Queue<T> queue(capacity);
    std::uint64_t sum = 0;
    std::thread consumer([&] {
      pinTo(1);
      std::array<T, kBatch> out;
      Poll poll;
      for (std::uint64_t received = 0; received < messages;) {
        const std::size_t n = queue.tryPopN(out);
        if (n == 0) poll();
        for (std::size_t i = 0; i < n; ++i) sum += sequenceOf(out[i]);
        received += n;
      }
    });
    std::array<T, kBatch> batch;
    Poll poll;
    for (std::uint64_t sent = 0; sent < messages;) {
      const std::size_t want = std::min<std::uint64_t>(kBatch, messages - sent);
      for (std::size_t i = 0; i < want; ++i) batch[i] = makeMessage<T>(sent + i);
      std::size_t done = 0;
      while (done < want) {
        const std::size_t n = queue.tryPushN(std::span<const T>(batch.data() + done, want - done));
        if (n == 0) poll();
        done += n;
      }
      sent += want;
    }
    consumer.join();
    if (sum != messages * (messages - 1) / 2) state.SkipWithError("lost or duplicated messages");
  }
  unpin();
  setMessageCounters(state, messages * state.iterations(), sizeof(T));
}

void capacities(benchmark::internal::Benchmark* b) {
  for (int capacity : {1, 16, 128, 1024, 4096}) b->Arg(capacity);
  b->Iterations(2)->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(Throughput<RaycubeBare, SmallMessage>)->Name("Throughput/8B/raycube")->Apply(capacities);
BENCHMARK(Throughput<Tbb, SmallMessage>)->Name("Throughput/8B/tbb")->Apply(capacities);
BENCHMARK(Throughput<MutexCv, SmallMessage>)->Name("Throughput/8B/mutex+cv")->Apply(capacities);

// Per message type: the bare ring, with doorbells, with doorbells and accounting (the machine's FIFO), one
// message at a time and in batches of 16 (the node sends one ray, or its whole waiting list).
template <class T>
bool registerRayThroughput(const std::string& type) {
  const auto add = [&](const std::string& queue, auto function) {
    benchmark::RegisterBenchmark(("Throughput/" + type + "/" + queue).c_str(), function)->Apply(capacities);
  };
  add("raycube", Throughput<RaycubeBare, T>);
  add("raycube+doorbells", Throughput<RaycubeBells, T>);
  add("raycube+doorbells+accounting", Throughput<RaycubeMachine, T>);
  add("raycube+doorbells,batch16", ThroughputBatched<RaycubeBells, T>);
  add("raycube+doorbells+accounting,batch16", ThroughputBatched<RaycubeMachine, T>);
  return true;
}
const bool kDoubleRayRegistered = registerRayThroughput<DoubleRay>("ray128B");
const bool kFloatRayRegistered = registerRayThroughput<FloatRay>("ray80B");
BENCHMARK(Throughput<Tbb, DoubleRay>)->Name("Throughput/ray128B/tbb")->Apply(capacities);
BENCHMARK(Throughput<MutexCv, DoubleRay>)->Name("Throughput/ray128B/mutex+cv")->Apply(capacities);

// ---- Saturation: the consumer is `ratio` times slower than the producer.

constexpr int kProducerWork = 100;  // units per message, roughly 100-300 ns

void Saturation(benchmark::State& state) {
  const auto capacity = static_cast<std::size_t>(state.range(0));
  const double ratio = static_cast<double>(state.range(1)) / 100.0;
  const int consumerWork = static_cast<int>(kProducerWork * ratio);
  constexpr std::uint64_t kMessages = 100'000;
  QueueStats total;
  double producerSeconds = 0;
  pinTo(0);
  for (auto _ : state) {
    Doorbell consumerBell, producerBell;
    SpscQueue<DoubleRay, Accounting::kOn> queue(
        {.capacity = capacity, .consumerBell = &consumerBell, .producerBell = &producerBell});
    std::thread consumer([&] {
      pinTo(1);
      for (std::uint64_t i = 0; i < kMessages; ++i) {
        benchmark::DoNotOptimize(queue.pop());
        work(consumerWork);
      }
    });
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t i = 0; i < kMessages; ++i) {
      work(kProducerWork);
      queue.push(makeMessage<DoubleRay>(i));
    }
    producerSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    consumer.join();
    total += queue.stats();
  }
  unpin();
  setMessageCounters(state, kMessages * state.iterations(), sizeof(DoubleRay));
  state.counters["blocked_frac"] = 1e-9 * static_cast<double>(total.nanosBlockedFull) / producerSeconds;
  state.counters["mean_occupancy"] = total.meanOccupancy();
  state.counters["occupancy_frac"] = total.meanOccupancy() / static_cast<double>(capacity);
}

BENCHMARK(Saturation)
    ->ArgNames({"capacity", "ratio_x100"})
    ->ArgsProduct({{128}, {25, 50, 100, 150, 200, 400, 800}})
    ->Args({8, 100})
    ->Args({8, 400})
    ->Iterations(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// ---- Oversubscription: N producer/consumer pairs share 2 cores and must sleep, not spin.

template <template <class> class Queue>
void Oversubscribed(benchmark::State& state) {
  const auto pairs = static_cast<std::size_t>(state.range(0));
  constexpr std::uint64_t kTotalMessages = 1 << 19;
  const std::uint64_t perPair = kTotalMessages / pairs;
  double cpuSeconds = 0;
  for (auto _ : state) {
    std::vector<std::unique_ptr<Queue<DoubleRay>>> queues;
    for (std::size_t p = 0; p < pairs; ++p) queues.push_back(std::make_unique<Queue<DoubleRay>>(128));
    const double cpuStart = processCpuSeconds();
    std::vector<std::thread> threads;
    for (std::size_t p = 0; p < pairs; ++p) {
      threads.emplace_back([&, p] {
        for (std::uint64_t i = 0; i < perPair; ++i) queues[p]->push(makeMessage<DoubleRay>(i));
      });
      threads.emplace_back([&, p] {
        std::uint64_t sum = 0;
        for (std::uint64_t i = 0; i < perPair; ++i) sum += sequenceOf(queues[p]->pop());
        benchmark::DoNotOptimize(sum);
      });
    }
    for (auto& t : threads) t.join();
    cpuSeconds += processCpuSeconds() - cpuStart;
  }
  const std::uint64_t messages = perPair * pairs * state.iterations();
  setMessageCounters(state, messages, sizeof(DoubleRay));
  state.counters["cpu_s_per_Mmsg"] = cpuSeconds / (static_cast<double>(messages) * 1e-6);
}

void pairCounts(benchmark::internal::Benchmark* b) {
  b->ArgName("pairs")->Arg(1)->Arg(8)->Arg(32)->Iterations(2)->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(Oversubscribed<RaycubeBells>)->Name("Oversubscribed/raycube")->Apply(pairCounts);
BENCHMARK(Oversubscribed<RaycubeBare>)->Name("Oversubscribed/raycube,no-sleep")->Apply(pairCounts);
BENCHMARK(Oversubscribed<Tbb>)->Name("Oversubscribed/tbb")->Apply(pairCounts);
BENCHMARK(Oversubscribed<MutexCv>)->Name("Oversubscribed/mutex+cv")->Apply(pairCounts);

// ---- Host channel: 64 nodes, one host. One SPSC queue per node vs one shared MPSC queue (oneTBB).

struct Contribution {
  std::uint32_t pixel = 0;
  float rgb[3] = {0, 0, 0};
};
constexpr std::size_t kNodes = 64;
constexpr std::size_t kBlock = 64;
constexpr std::uint64_t kContributionsPerNode = 1 << 15;

void HostChannelSpscPerNode(benchmark::State& state) {
  double cpuSeconds = 0;
  for (auto _ : state) {
    std::vector<Doorbell> bells(kNodes);
    std::vector<Doorbell*> bellPointers;
    for (auto& bell : bells) bellPointers.push_back(&bell);
    HostChannel<Contribution, kBlock> channel(kNodes, 8, bellPointers);
    const double cpuStart = processCpuSeconds();
    std::vector<std::thread> nodes;
    for (std::size_t n = 0; n < kNodes; ++n) {
      nodes.emplace_back([&, n] {
        auto sender = channel.sender(n);
        for (std::uint32_t i = 0; i < kContributionsPerNode; ++i) sender.send({i, {1, 1, 1}});
        sender.flush();
      });
    }
    std::uint64_t received = 0;
    while (received < kNodes * kContributionsPerNode) {
      waitUntil(channel.doorbell(), [&] { return channel.anyPending(); });
      received += channel.drain([](const Contribution& c) { benchmark::DoNotOptimize(c); });
    }
    for (auto& t : nodes) t.join();
    cpuSeconds += processCpuSeconds() - cpuStart;
  }
  const std::uint64_t contributions = kNodes * kContributionsPerNode * state.iterations();
  state.SetItemsProcessed(static_cast<std::int64_t>(contributions));
  state.counters["cpu_s_per_Mmsg"] = cpuSeconds / (static_cast<double>(contributions) * 1e-6);
}

void HostChannelSharedTbb(benchmark::State& state) {
  struct Block {
    std::uint32_t count = 0;
    std::array<Contribution, kBlock> items{};
  };
  double cpuSeconds = 0;
  for (auto _ : state) {
    tbb::concurrent_bounded_queue<Block> queue;
    queue.set_capacity(8 * kNodes);  // same total buffering as the SPSC channel
    const double cpuStart = processCpuSeconds();
    std::vector<std::thread> nodes;
    for (std::size_t n = 0; n < kNodes; ++n) {
      nodes.emplace_back([&] {
        Block block;
        for (std::uint32_t i = 0; i < kContributionsPerNode; ++i) {
          block.items[block.count++] = {i, {1, 1, 1}};
          if (block.count == kBlock) {
            queue.push(block);
            block.count = 0;
          }
        }
        if (block.count > 0) queue.push(block);
      });
    }
    std::uint64_t received = 0;
    Block block;
    while (received < kNodes * kContributionsPerNode) {
      queue.pop(block);
      for (std::uint32_t i = 0; i < block.count; ++i) benchmark::DoNotOptimize(block.items[i]);
      received += block.count;
    }
    for (auto& t : nodes) t.join();
    cpuSeconds += processCpuSeconds() - cpuStart;
  }
  const std::uint64_t contributions = kNodes * kContributionsPerNode * state.iterations();
  state.SetItemsProcessed(static_cast<std::int64_t>(contributions));
  state.counters["cpu_s_per_Mmsg"] = cpuSeconds / (static_cast<double>(contributions) * 1e-6);
}

BENCHMARK(HostChannelSpscPerNode)
    ->Name("HostChannel/64nodes/spsc-per-node")
    ->Iterations(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(HostChannelSharedTbb)
    ->Name("HostChannel/64nodes/shared-tbb-mpsc")
    ->Iterations(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace raycube::queues

BENCHMARK_MAIN();
