#include "host/engines/processor_thread.h"

#include <gtest/gtest.h>
#include <pthread.h>

#include <atomic>
#include <cstddef>
#include <latch>
#include <thread>
#include <vector>

namespace raycube::host {
namespace {

std::size_t ownStackBytes() {
  pthread_attr_t attributes;
  if (pthread_getattr_np(pthread_self(), &attributes) != 0) return 0;
  std::size_t bytes = 0;
  pthread_attr_getstacksize(&attributes, &bytes);
  pthread_attr_destroy(&attributes);
  return bytes;
}

TEST(ProcessorThreads, EveryBodyRunsOnceAndJoinAllWaitsForThemAll) {
  constexpr int kProcessors = 64;
  std::latch release(1);
  std::atomic<int> started{0};
  std::vector<int> ran(kProcessors, 0);
  ProcessorThreads threads;
  for (int id = 0; id < kProcessors; ++id)
    threads.start([&, id] {
      started.fetch_add(1);
      release.wait();  // none finishes before all have started
      ++ran[std::size_t(id)];
    });
  release.count_down();
  threads.joinAll();
  EXPECT_EQ(started.load(), kProcessors);
  EXPECT_EQ(ran, std::vector<int>(kProcessors, 1));
  threads.joinAll();  // nothing left to join: returns at once
}

TEST(ProcessorThreads, RunOnTheStackSizeAsked) {
  std::size_t byDefault = 0;  // a std::thread's: glibc's default (ThreadSanitizer enlarges small stacks)
  std::thread([&] { byDefault = ownStackBytes(); }).join();
  for (const std::size_t asked : {std::size_t(256) * 1024, kProcessorStackBytes}) {
    std::size_t seen = 0;
    ProcessorThreads threads(asked);
    threads.start([&] { seen = ownStackBytes(); });
    threads.joinAll();
    EXPECT_GE(seen, asked);
    EXPECT_LT(seen, byDefault) << "asked " << asked;
  }
  std::size_t seen = 0;
  ProcessorThreads large(byDefault * 2);
  large.start([&] { seen = ownStackBytes(); });
  large.joinAll();
  EXPECT_GE(seen, byDefault * 2);
}

}  // namespace
}  // namespace raycube::host
