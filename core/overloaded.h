#pragma once
// The usual visitor helper: one callable from several lambdas, for std::visit over a Shape.

namespace raycube::core {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// C++20 deduces this for aggregates; clang 14 (the fuzz preset's compiler) still needs the guide.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace raycube::core
