// The mesh stiffness of the paper's gear pair at the pitch point, from an
// installed gearimpact. Prints Ke in N/m; exits non-zero on an error.
#include <cstdio>
#include <exception>

#include "gearimpact/gearimpact.hpp"

int main() {
  try {
    const gearimpact::GearPair pair = gearimpact::paper_gear_pair();
    const double x_m = gearimpact::pitch_point_position(pair);
    const gearimpact::MeshStiffness k = gearimpact::mesh_stiffness(pair, x_m);
    std::printf("mesh stiffness at the pitch point (x = %.6g m): Ke = %.17g N/m\n", x_m, k.ke);
    return k.ke > 0.0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
