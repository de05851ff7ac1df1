#pragma once
// Rays a full neighbour FIFO refused, kept in order until it has room (the deadlock answer of
// LogicalProcessor::send). A queue of fixed chunks: it holds what waits now, give or take a chunk, and hands
// back each chunk as it drains. A vector with a moving head held up to four times the most rays that ever
// waited (its front reclaimed only at half, its capacity doubled on top), and kept it to the end, though
// the processors' lists peak at different times.
#include <algorithm>
#include <cstddef>
#include <deque>
#include <memory>
#include <span>

namespace raycube::node {

template <class T>
class OverflowList {
 public:
  // 8 KB of 128-byte rays: a ray's worth of bookkeeping per 64 rays, and a full neighbour's FIFO (128 on
  // the iPSC) takes two chunks at a time.
  static constexpr std::size_t kChunk = 64;

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  std::size_t chunks() const { return chunks_.size(); }  // each kChunk items
  const T& front() const { return chunks_.front()[head_]; }
  // The oldest waiting items that lie side by side: those of the first chunk (the rest follow once these
  // are popped).
  std::span<const T> oldest() const {
    if (empty()) return {};
    return std::span<const T>(chunks_.front().get() + head_, std::min(size_, kChunk - head_));
  }
  void push_back(const T& item) {
    const std::size_t at = head_ + size_;
    if (at == chunks_.size() * kChunk) chunks_.push_back(newChunk());
    chunks_[at / kChunk][at % kChunk] = item;
    ++size_;
  }
  // Drops the n oldest (n <= size()).
  void pop_front(std::size_t n = 1) {
    size_ -= n;
    head_ += n;
    while (head_ >= kChunk || (size_ == 0 && !chunks_.empty())) {
      release(std::move(chunks_.front()));
      chunks_.pop_front();
      head_ = size_ == 0 ? 0 : head_ - kChunk;
    }
  }

 private:
  std::unique_ptr<T[]> newChunk() {
    if (spare_) return std::move(spare_);
    return std::make_unique_for_overwrite<T[]>(kChunk);
  }
  // One drained chunk is kept for the next burst; the others go back to the allocator.
  void release(std::unique_ptr<T[]> chunk) {
    if (!spare_) spare_ = std::move(chunk);
  }

  std::deque<std::unique_ptr<T[]>> chunks_;
  std::unique_ptr<T[]> spare_;
  std::size_t head_ = 0;  // first waiting item, in chunks_.front()
  std::size_t size_ = 0;
};

}  // namespace raycube::node
