#pragma once
// Shared by every test program: the sanitizer switch, a watchdog that fails a hung test rather than hang CI,
// and the repository's own files. Only the standard library and GoogleTest: the queue tests link nothing
// but the queues.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

namespace raycube::testing_support {

// Sanitized builds run 5-50x slower: tests shrink. The tsan and asan presets set RAYCUBE_SANITIZED=1; a
// sanitized program run by hand shrinks too.
inline bool sanitized() {
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
  return true;
#else
  const char* value = std::getenv("RAYCUBE_SANITIZED");
  return value != nullptr && std::string(value) == "1";
#endif
}

// Full counts in release; sanitized builds get a smaller but still racy workload.
inline std::uint64_t scaled(std::uint64_t release, std::uint64_t sanitizedCount) {
  return sanitized() ? sanitizedCount : release;
}

// A render or exchange that has not finished by then is deadlocked or has lost a wake-up or its termination.
inline std::chrono::seconds watchdogLimit() {
  return std::chrono::seconds(sanitized() ? 600 : 120);
}

// body() on a worker thread, returning what it returns (or rethrowing what it throws). If it has not
// finished within limit, the test fails, says why, and the program ends rather than hang CI.
template <class Body>
auto runWatched(std::chrono::seconds limit, const std::string& why, Body&& body) -> decltype(body()) {
  using Result = decltype(body());
  std::packaged_task<Result()> task(std::forward<Body>(body));
  std::future<Result> done = task.get_future();
  std::thread worker(std::move(task));
  if (done.wait_for(limit) != std::future_status::ready) {
    ADD_FAILURE() << "WATCHDOG: not finished after " << limit.count() << " s: " << why;
    std::fprintf(stderr, "WATCHDOG: not finished after %lld s: %s; ending the test program\n",
                 static_cast<long long>(limit.count()), why.c_str());
    std::fflush(stderr);
    std::_Exit(1);
  }
  worker.join();
  return done.get();
}

// A file of the repository (tests/CMakeLists.txt sets RAYCUBE_SOURCE_DIR): tests read nothing outside it.
inline std::filesystem::path sourcePath(const std::filesystem::path& relative) {
  return std::filesystem::path(RAYCUBE_SOURCE_DIR) / relative;
}
inline std::filesystem::path scenePath(const std::string& file) {
  return sourcePath("scenes") / file;
}

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace raycube::testing_support
