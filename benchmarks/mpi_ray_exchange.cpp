// Ray messages per second from one processor to its neighbour through the machine's interconnect, FIFO
// capacity 128: on two MPI ranks with rays batched per MPI message (--ray-batch 16, the default) and
// unbatched (1), beside the same two processors on one rank (the shared-memory FIFO). Rank 0 (the host)
// only waits. Not a test: a measurement (README, The machine over MPI).
//   mpirun -np 3 build/release/benchmarks/mpi_ray_exchange [RAYS (default 2000000)] [RUNS (default 5)]
#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "core/view.h"
#include "node/region_map.h"
#include "queues/interconnects/mpi_interconnect.h"

using namespace raycube;
using Message = node::BasicRayMessage<double>;
using Clock = std::chrono::steady_clock;

namespace {

struct Config {
  const char* name;
  std::vector<int> rankOf;  // processors 0 (sender) and 1 (receiver)
  std::size_t rayBatch;
};

// Every rank waits for the others while rank 0 keeps taking (and dropping) what arrives; the other ranks
// take nothing here: a ray from a rank that left the barrier first belongs to the next exchange.
void barrier(queues::MpiLink& link) {
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  for (int done = 0; !done;) {
    const std::size_t n = link.rank() == 0 ? link.poll([](int, queues::Packet, std::span<const char>) {}) : 0;
    link.progressSends();
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (n == 0 && !done)
      std::this_thread::sleep_for(std::chrono::microseconds(200));  // leave the cores to the exchange
  }
}

// One exchange of `rays` rays; returns the seconds the receiver took (on the receiver's rank, else 0).
double exchange(queues::MpiLink& link, const node::RegionMap& regions, const Config& config, long rays) {
  queues::MpiInterconnect<double> net(regions, queues::MpiWiring{config.rankOf, 128, config.rayBatch}, link);
  std::atomic<int> running{0};
  std::atomic<double> seconds{0};
  std::vector<std::thread> threads;
  barrier(link);
  const auto start = Clock::now();
  if (net.local(0)) {
    ++running;
    threads.emplace_back([&] {
      std::vector<Message> burst(64);
      for (Message& m : burst) m.destination = 1;
      for (long sent = 0; sent < rays;) {
        const std::size_t n = net.endpoint(0).trySend(
            1, std::span<const Message>(burst).first(std::size_t(std::min<long>(64, rays - sent))));
        sent += long(n);
        if (n == 0) net.waitFor(0, [&] { return net.endpoint(0).canSend(1); });
      }
      --running;
    });
  }
  if (net.local(1)) {
    ++running;
    threads.emplace_back([&] {
      std::vector<Message> inbox(64);
      for (long received = 0; received < rays;) {
        const std::size_t n = net.endpoint(1).receive(inbox);
        received += long(n);
        if (n == 0) net.waitFor(1, [&] { return net.endpoint(1).anyIncoming(); });
      }
      seconds = std::chrono::duration<double>(Clock::now() - start).count();
      net.endpoint(1).announceTermination();
      --running;
    });
  }
  typename queues::MpiInterconnect<double>::ServeHooks hooks;
  hooks.stopped = [&] { return running.load() == 0; };
  hooks.progress = [] { return std::vector<queues::ProcessorProgress>{}; };
  if (link.rank() != 0) net.serve(hooks);
  for (std::thread& t : threads) t.join();
  barrier(link);
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  {
    queues::MpiLink link;
    if (link.size() != 3) {
      if (link.rank() == 0)
        std::fprintf(stderr, "run with mpirun -np 3 (rank 0 waits, ranks 1 and 2 exchange)\n");
      MPI_Finalize();
      return 2;
    }
    const long rays = argc > 1 ? std::atol(argv[1]) : 2'000'000;
    const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
    const core::View view(core::Camera{}, 2, 1, core::Sampling::Centers);
    const node::RegionMap regions = node::RegionMap::grid({0, 1, 2}, {0, 1}, node::ScreenLines(view));
    std::vector<Config> configs = {{"shared-memory FIFO (one rank)", {1, 1}, 16},
                                   {"two ranks, batched 16", {1, 2}, 16},
                                   {"two ranks, unbatched", {1, 2}, 1}};
    if (argc > 3) configs = {configs[std::size_t(std::atoi(argv[3]))]};
    std::uint32_t job = 0;
    for (const Config& config : configs) {
      std::vector<double> rates;
      for (int run = 0; run < runs; ++run) {
        link.setJob(++job);
        const double seconds = exchange(link, regions, config, rays);
        double slowest = 0;
        MPI_Reduce(&seconds, &slowest, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
        rates.push_back(double(rays) / slowest);
      }
      std::sort(rates.begin(), rates.end());
      if (link.rank() == 0)
        std::printf("%-32s median %6.2f M rays/s (min %.2f, max %.2f; %ld rays of %zu bytes, %d runs)\n",
                    config.name, rates[rates.size() / 2] / 1e6, rates.front() / 1e6, rates.back() / 1e6, rays,
                    sizeof(Message), runs);
    }
  }
  MPI_Finalize();
  return 0;
}
