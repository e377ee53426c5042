// Mathematical constants the library shares. The library is C++17, so
// std::numbers (C++20) is not available to it.
#pragma once

namespace gearimpact {

// The double nearest pi (the same value as C++20's std::numbers::pi).
inline constexpr double pi = 3.141592653589793238462643383279502884;

}  // namespace gearimpact
