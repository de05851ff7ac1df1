// The rays a node holds for a full neighbour (node/overflow_list.h): kept in order across its chunks, and
// no more held than what waits now, give or take a chunk at each end.
#include "node/overflow_list.h"

#include <gtest/gtest.h>

#include <deque>
#include <random>

namespace raycube::node {
namespace {

// Pops up to n from the list the way a node's flush does (the oldest run, then the next), checking order.
std::size_t drain(OverflowList<int>& list, std::size_t n, std::deque<int>& expected) {
  std::size_t popped = 0;
  while (popped < n && !list.empty()) {
    const auto run = list.oldest();
    const std::size_t take = std::min(run.size(), n - popped);
    for (std::size_t k = 0; k < take; ++k) {
      EXPECT_EQ(run[k], expected.front());
      expected.pop_front();
    }
    list.pop_front(take);
    popped += take;
  }
  return popped;
}

constexpr std::size_t kChunk = OverflowList<int>::kChunk;

TEST(OverflowList, KeepsOrderAndHoldsOnlyWhatWaits) {
  OverflowList<int> list;
  std::deque<int> expected;
  std::mt19937 random(7);
  int next = 0;
  std::size_t mostWaiting = 0;
  for (int round = 0; round < 2000; ++round) {
    const int pushes = int(random() % 40);
    for (int k = 0; k < pushes; ++k) {
      list.push_back(next);
      expected.push_back(next++);
    }
    mostWaiting = std::max(mostWaiting, list.size());
    drain(list, random() % 40, expected);
    ASSERT_EQ(list.size(), expected.size());
    ASSERT_EQ(list.empty(), expected.empty());
    if (!list.empty()) {
      ASSERT_EQ(list.front(), expected.front());
    }
    // A partly used chunk at each end at most.
    ASSERT_LE(list.chunks() * kChunk, list.size() + 2 * kChunk);
  }
  EXPECT_GT(mostWaiting, 4 * kChunk);  // the random walk spanned several chunks
  drain(list, list.size(), expected);
  EXPECT_TRUE(list.empty());
  EXPECT_TRUE(expected.empty());
  EXPECT_EQ(list.chunks(), 0u);  // every chunk handed back once drained
}

TEST(OverflowList, OldestRunStopsAtTheChunksEnd) {
  OverflowList<int> list;
  for (int k = 0; k < int(kChunk) + 8; ++k) list.push_back(k);
  list.pop_front(kChunk - 4);
  EXPECT_EQ(list.size(), 12u);
  ASSERT_EQ(list.oldest().size(), 4u);  // the first chunk's last four
  EXPECT_EQ(list.oldest()[0], int(kChunk) - 4);
  list.pop_front(4);
  EXPECT_EQ(list.chunks(), 1u);
  ASSERT_EQ(list.oldest().size(), 8u);  // then the second chunk's
  EXPECT_EQ(list.oldest()[0], int(kChunk));
}

TEST(OverflowList, PopsAcrossChunksAtOnce) {
  OverflowList<int> list;
  for (int k = 0; k < int(3 * kChunk); ++k) list.push_back(k);
  list.pop_front(2 * kChunk + 5);
  EXPECT_EQ(list.front(), int(2 * kChunk) + 5);
  EXPECT_EQ(list.chunks(), 1u);
  list.pop_front(list.size());
  EXPECT_TRUE(list.empty());
  EXPECT_TRUE(list.oldest().empty());
  list.push_back(42);  // reuses the kept chunk
  EXPECT_EQ(list.front(), 42);
}

}  // namespace
}  // namespace raycube::node
