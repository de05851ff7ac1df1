#pragma once
// A logical processor's thread (3.5: its synthesis and communication tasks), with a stack of its own size.
// 64 processors start and end with every run of an 8 x 8 machine, and what a thread costs to start is
// mostly its stack's: glibc's default of 8 MB puts every stack under a page table of its own, allocated
// and freed with the thread, and keeps only five such stacks for reuse. Small stacks make 64 threads start
// and end several times faster (std::thread cannot be given a stack size).
#include <pthread.h>

#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace raycube::host {

// A node's deepest call chain (a step: receive, evaluate, walk, traverse, shade, deliver, send) holds a
// few kilobytes; nothing in it recurses. Every machine test (threads and MPI ranks, ray trees 64 deep) passes
// with 32 KB.
inline constexpr std::size_t kProcessorStackBytes = 512 * 1024;

// The processors' threads of one run: each started with its body, all joined together.
class ProcessorThreads {
 public:
  explicit ProcessorThreads(std::size_t stackBytes = kProcessorStackBytes) : stackBytes_(stackBytes) {}
  ProcessorThreads(const ProcessorThreads&) = delete;
  ProcessorThreads& operator=(const ProcessorThreads&) = delete;
  // As std::thread's: threads still running when their owner goes (an exception before joinAll) end the
  // program, rather than hang it on a processor waiting for rays that will never come.
  ~ProcessorThreads() {
    if (!threads_.empty()) std::terminate();
  }

  void start(std::function<void()> body) {
    bodies_.push_back(std::make_unique<std::function<void()>>(std::move(body)));
    pthread_attr_t attributes;
    pthread_attr_init(&attributes);
    pthread_attr_setstacksize(&attributes, stackBytes_);
    pthread_t thread;
    const int error = pthread_create(&thread, &attributes, &ProcessorThreads::run, bodies_.back().get());
    pthread_attr_destroy(&attributes);
    if (error != 0) {
      bodies_.pop_back();
      throw std::runtime_error("cannot start a processor's thread (pthread_create: error " +
                               std::to_string(error) + ")");
    }
    threads_.push_back(thread);
  }

  void joinAll() {
    for (pthread_t thread : threads_) pthread_join(thread, nullptr);
    threads_.clear();
  }

 private:
  // An exception leaving a body ends the program, as it would leaving a std::thread's.
  static void* run(void* body) noexcept {
    (*static_cast<std::function<void()>*>(body))();
    return nullptr;
  }

  std::size_t stackBytes_;
  std::vector<std::unique_ptr<std::function<void()>>> bodies_;
  std::vector<pthread_t> threads_;
};

}  // namespace raycube::host
