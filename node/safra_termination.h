#pragma once
// Termination detection (Priol & Bouatouch 3.6), made safe for messages in flight with Safra's counting
// variant of the Dijkstra-Feijen-van Gasteren token ring (EWD 998). Every node counts the rays it sent
// minus the rays it received; the token sums those counts round the ring and turns black when it passes a
// node that received a ray since the token's last visit. A white token that comes back to processor 0 with
// a zero sum, processor 0 itself white and passive, proves that every node is passive and no ray is in a
// FIFO. The class is the bookkeeping only: who moves the token, and when a node is passive, is the
// caller's business.
#include <cstdint>

namespace raycube::node {

struct Token {
  bool black = false;
  std::int64_t count = 0;  // sum of (rays sent - rays received) of the nodes visited this round
};

class SafraTermination {
 public:
  enum class Decision : std::uint8_t {
    PassToken,          // hand token() to the next node on the ring
    AnnounceTermination  // processor 0 only: the round proved that the machine has finished
  };

  explicit SafraTermination(int id) : initiator_(id == 0), holding_(id == 0) {}

  // EWD 998: a ray is counted when it enters the neighbour's FIFO, and again when it leaves it.
  void countSent() { ++balance_; }
  void countReceived() {
    --balance_;
    black_ = true;  // the receipt may have re-activated this node behind the token's back
  }

  bool holdsToken() const { return holding_; }
  void takeToken(const Token& token) {
    token_ = token;
    holding_ = true;
    ++visits_;
  }

  // Call only while holding the token and passive. Processor 0 either proves termination or starts a new
  // round; any other node adds its count and colour. After PassToken the node no longer holds the token.
  Decision release() {
    if (initiator_) {
      if (roundUnderway_ && !token_.black && !black_ && token_.count + balance_ == 0)
        return Decision::AnnounceTermination;
      token_ = Token{};
      roundUnderway_ = true;
      ++rounds_;
    } else {
      token_.count += balance_;
      token_.black = token_.black || black_;
    }
    black_ = false;
    holding_ = false;
    return Decision::PassToken;
  }
  const Token& token() const { return token_; }

  std::uint32_t roundsStarted() const { return rounds_; }  // processor 0: token rounds
  std::uint64_t visits() const { return visits_; }         // times the token arrived here
  std::int64_t balance() const { return balance_; }

 private:
  bool initiator_;
  bool holding_;  // 3.6: at the start processor 0 holds the token
  bool roundUnderway_ = false;
  bool black_ = false;
  std::int64_t balance_ = 0;
  Token token_;
  std::uint32_t rounds_ = 0;
  std::uint64_t visits_ = 0;
};

}  // namespace raycube::node
