#include "queues/doorbell.h"

#if defined(__linux__)
#include <linux/membarrier.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace raycube::queues {

bool asymmetricFencesAvailable() {
#if defined(__linux__) && defined(SYS_membarrier)
  static const bool available = syscall(SYS_membarrier, MEMBARRIER_CMD_REGISTER_PRIVATE_EXPEDITED, 0, 0) == 0;
  return available;
#else
  return false;
#endif
}

namespace {
// Registering costs an RCU grace period (about 10 ms measured) once the process has a second thread, and
// nothing before: register while the program starts, single-threaded, not when the first doorbell is made.
[[maybe_unused]] const bool registeredAtStart = asymmetricFencesAvailable();
}  // namespace

// Forces a full barrier on every CPU running one of our threads; a thread that is not running has passed
// one in its context switch. So a ringer's store before its sleeper-count load is visible to us now.
void Doorbell::heavyFence() const {
#if defined(__linux__) && defined(SYS_membarrier)
  if (asymmetric_ && syscall(SYS_membarrier, MEMBARRIER_CMD_PRIVATE_EXPEDITED, 0, 0) == 0) return;
#endif
  seqCstFence();
}

}  // namespace raycube::queues
