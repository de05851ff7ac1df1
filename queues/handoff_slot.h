#pragma once
// One value handed from one thread to another through a single slot: where Safra's token waits for its
// processor (2.2), or for the communication task that sends it to another rank. Only one token exists, so a
// put always finds the slot empty.
#include <atomic>

namespace raycube::queues {

template <class T>
class HandoffSlot {
 public:
  bool holds() const { return full_.load(std::memory_order_acquire); }
  // Leaves the value here; the slot must be empty.
  void put(const T& value) {
    value_ = value;
    full_.store(true, std::memory_order_release);
  }
  // Takes the value if one is here.
  bool take(T& value) {
    if (!full_.load(std::memory_order_acquire)) return false;
    value = value_;
    full_.store(false, std::memory_order_release);
    return true;
  }

 private:
  std::atomic<bool> full_{false};
  T value_{};
};

}  // namespace raycube::queues
