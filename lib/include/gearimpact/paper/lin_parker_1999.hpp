// The published natural frequencies of Lin & Parker's (1999) example planetary system
// (J. Vib. Acoust. 121:316-321, Table 2; Lin's thesis Table C.1), as transcribed in
// gfsReboucas/Drivetrain-python tests/test_lin_parker_1999.py (the paper itself not read here),
// in Hz to the printed 0.1 Hz. The system's parameters are examples/planetary_lp99.toml's
// (docs/planetary.md). The suites and `gearimpact reproduce` compare the linear stage's modes
// (modes/planetary.hpp) with it.
#pragma once

#include <array>

namespace gearimpact {

struct LinParker1999Table {
  int planets = 0;  // N, equally spaced
  // The distinct rotational frequencies (the rigid mode first) and the translational ones (each
  // double), ascending.
  std::array<double, 6> rotational{};
  std::array<double, 6> translational{};
};

inline constexpr std::array<LinParker1999Table, 3> kLinParker1999{{
    {3,
     {0.0, 1475.7, 1930.3, 2658.3, 7462.8, 11775.3},
     {743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9}},
    {4,
     {0.0, 1536.6, 1970.6, 2625.7, 7773.6, 13071.1},
     {727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6}},
    {5,
     {0.0, 1567.4, 2006.1, 2614.8, 8065.4, 14253.1},
     {710.0, 1072.0, 1888.1, 2425.3, 7382.4, 11172.3}},
}};

// The planet modes' frequencies, each of multiplicity N - 3 (none for N = 3), the same for every N.
inline constexpr std::array<double, 3> kLinParker1999Planet{1808.2, 5963.8, 6981.7};

}  // namespace gearimpact
