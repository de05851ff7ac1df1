#pragma once
// Values, vectors and strings as bytes in the machine's own layout (every address space runs the same
// binary on the same kind of host), over any byte sink or source: a buffer for MPI messages
// (host/engines/machine_wire.h), a pipe for the simulation's results
// (host/engines/simgrid/emulated_machine.cpp).
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace raycube::host {

// Sink: void write(const char* data, std::size_t n).
template <class Sink>
class WireEncoder {
 public:
  template <class... Args>
  explicit WireEncoder(Args&&... args) : sink_(std::forward<Args>(args)...) {}
  void bytes(const void* data, std::size_t n) {
    if (n > 0) sink_.write(static_cast<const char*>(data), n);  // data may be null (an empty vector's)
  }
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof v);
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(std::uint64_t(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
  void string(const std::string& s) { vector(std::vector<char>(s.begin(), s.end())); }
  Sink& sink() { return sink_; }

 private:
  Sink sink_;
};

// Source: void read(char* data, std::size_t n), throwing when fewer bytes come; and
// void expect(std::size_t n), throwing when it knows fewer than n bytes remain (so a corrupt length never
// allocates).
template <class Source>
class WireDecoder {
 public:
  template <class... Args>
  explicit WireDecoder(Args&&... args) : source_(std::forward<Args>(args)...) {}
  void bytes(void* data, std::size_t n) {
    if (n > 0) source_.read(static_cast<char*>(data), n);  // memcpy must not see an empty vector's null
  }
  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    std::array<char, sizeof(T)> raw;  // T need not be default-constructible (core::View)
    bytes(raw.data(), raw.size());
    return std::bit_cast<T>(raw);
  }
  template <class T>
  std::vector<T> vector() {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = value<std::uint64_t>();
    constexpr std::size_t kMost =
        std::numeric_limits<std::size_t>::max() / std::max<std::size_t>(1, sizeof(T));
    source_.expect(n > kMost ? std::numeric_limits<std::size_t>::max() : n * sizeof(T));
    std::vector<T> v(n);
    bytes(v.data(), n * sizeof(T));
    return v;
  }
  std::string string() {
    const auto chars = vector<char>();
    return std::string(chars.begin(), chars.end());
  }

 private:
  Source source_;
};

}  // namespace raycube::host
