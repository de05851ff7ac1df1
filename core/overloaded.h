#pragma once
// The usual visitor helper: one callable from several lambdas, for std::visit over a Shape.

namespace raycube::core {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

}  // namespace raycube::core
