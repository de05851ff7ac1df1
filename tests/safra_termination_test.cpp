// Safra's token bookkeeping (node/safra_termination.h) on its own: a ring driven by hand.
#include "node/safra_termination.h"

#include <gtest/gtest.h>

#include <vector>

namespace raycube::node {
namespace {

using Decision = SafraTermination::Decision;

// A ring of passive nodes; the token goes round in order. Returns what processor 0 decided at the end of
// the round (after starting it, if it had to).
struct Ring {
  explicit Ring(int n) {
    for (int id = 0; id < n; ++id) nodes.emplace_back(id);
  }
  // The token goes from processor 0 round the ring and back (processor 0 first starts a round if none is
  // underway); returns what processor 0 then decides.
  Decision round() {
    if (!roundUnderway) {
      EXPECT_TRUE(nodes[0].holdsToken());
      if (nodes[0].release() == Decision::AnnounceTermination) return Decision::AnnounceTermination;
    }
    Token t = nodes[0].token();
    for (std::size_t id = 1; id < nodes.size(); ++id) {
      nodes[id].takeToken(t);
      EXPECT_EQ(nodes[id].release(), Decision::PassToken);
      EXPECT_FALSE(nodes[id].holdsToken());
      t = nodes[id].token();
    }
    nodes[0].takeToken(t);
    const Decision d = nodes[0].release();
    roundUnderway = d == Decision::PassToken;
    return d;
  }
  bool roundUnderway = false;
  std::vector<SafraTermination> nodes;
};

TEST(SafraTermination, ProcessorZeroHoldsTheTokenAtTheStartAndNoOtherDoes) {
  Ring ring(4);
  EXPECT_TRUE(ring.nodes[0].holdsToken());
  for (int id = 1; id < 4; ++id) EXPECT_FALSE(ring.nodes[id].holdsToken());
}

TEST(SafraTermination, NeverAnnouncesBeforeAFullRound) {
  SafraTermination alone(0);
  EXPECT_EQ(alone.release(), Decision::PassToken);  // starts round 1
  EXPECT_EQ(alone.roundsStarted(), 1u);
  alone.takeToken(alone.token());
  EXPECT_EQ(alone.release(), Decision::AnnounceTermination);
}

TEST(SafraTermination, QuietRingTerminatesAfterOneRound) {
  Ring ring(5);
  EXPECT_EQ(ring.round(), Decision::AnnounceTermination);
  EXPECT_EQ(ring.nodes[0].roundsStarted(), 1u);
  for (int id = 1; id < 5; ++id) EXPECT_EQ(ring.nodes[id].visits(), 1u);
}

TEST(SafraTermination, ARayInFlightKeepsTheMachineAlive) {
  Ring ring(3);
  ring.nodes[2].countSent();  // a ray towards processor 1, still in its FIFO: the sum is +1
  EXPECT_EQ(ring.round(), Decision::PassToken);
  ring.nodes[1].countReceived();  // it arrives: processor 1 turns black
  EXPECT_EQ(ring.round(), Decision::PassToken);  // black token
  EXPECT_EQ(ring.round(), Decision::AnnounceTermination);
  EXPECT_EQ(ring.nodes[0].roundsStarted(), 3u);
}

TEST(SafraTermination, AReceiptBehindTheTokensBackTurnsTheRoundBlack) {
  Ring ring(3);
  // Processor 1 sends to processor 2 and processor 2 receives, both counted before the token visits: the sum
  // is zero but processor 2 may have been re-activated, so the round must not prove termination.
  ring.nodes[1].countSent();
  ring.nodes[2].countReceived();
  EXPECT_EQ(ring.round(), Decision::PassToken);
  EXPECT_EQ(ring.round(), Decision::AnnounceTermination);
}

TEST(SafraTermination, ProcessorZeroWhoReceivedKeepsTheRoundOpen) {
  Ring ring(2);
  ring.nodes[1].countSent();
  EXPECT_EQ(ring.round(), Decision::PassToken);  // count +1
  ring.nodes[0].countReceived();                 // processor 0 black, balance -1: sum 0 but black
  EXPECT_EQ(ring.round(), Decision::PassToken);
  EXPECT_EQ(ring.round(), Decision::AnnounceTermination);
}

TEST(SafraTermination, CountsSumAcrossTheRing) {
  Ring ring(4);
  ring.nodes[1].countSent();
  ring.nodes[1].countSent();
  ring.nodes[3].countReceived();
  ASSERT_EQ(ring.nodes[0].release(), Decision::PassToken);
  Token t = ring.nodes[0].token();
  for (int id = 1; id < 4; ++id) {
    ring.nodes[id].takeToken(t);
    ring.nodes[id].release();
    t = ring.nodes[id].token();
  }
  EXPECT_EQ(t.count, 1);
  EXPECT_TRUE(t.black);
}

}  // namespace
}  // namespace raycube::node
