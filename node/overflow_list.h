#pragma once
// Rays a full neighbour FIFO refused, kept in order until it has room (the deadlock answer of
// LogicalProcessor::send). A vector with a moving head: no allocation once it has grown to its peak.
#include <cstddef>
#include <span>
#include <vector>

namespace raycube::node {

template <class T>
class OverflowList {
 public:
  bool empty() const { return head_ == items_.size(); }
  std::size_t size() const { return items_.size() - head_; }
  const T& front() const { return items_[head_]; }
  std::span<const T> all() const { return std::span<const T>(items_).subspan(head_); }
  void push_back(const T& item) { items_.push_back(item); }
  void pop_front(std::size_t n = 1) {
    head_ += n;
    if (head_ == items_.size()) {
      items_.clear();
      head_ = 0;
    } else if (head_ >= kCompactAfter && head_ * 2 >= items_.size()) {
      items_.erase(items_.begin(), items_.begin() + std::ptrdiff_t(head_));  // never empty: reclaim the front
      head_ = 0;
    }
  }

 private:
  static constexpr std::size_t kCompactAfter = 1024;
  std::vector<T> items_;
  std::size_t head_ = 0;
};

}  // namespace raycube::node
