// libFuzzer target for the merge's reader of a shard's sweep.csv. The contract under test: any
// bytes give either rows or an InputError, never a crash, hang, other exception or sanitizer
// report; rows read are inside the spec's grids with finite figures; and rows read write back to
// text that reads to the same text (write -> read -> write is a fixed point).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/io/sweep_files.hpp"

namespace {

// Two lines of three points from 0 to 1, both directions: what the seed corpus was written for.
gearimpact::SteadySweepRecord spec() {
  gearimpact::SteadySweepRecord s;
  s.vary = "initial.w1";
  s.from_si = 0.0;
  s.to_si = 1.0;
  s.points = 3;
  s.lines = 2;
  s.directions = {gearimpact::SweepDirection::up, gearimpact::SweepDirection::down};
  return s;
}

bool finite_or_absent(const std::optional<double>& v) {
  return !v || std::isfinite(*v);
}

[[noreturn]] void broken(const char* what, const std::string& text) {
  std::fprintf(stderr, "%s:\n%s\n", what, text.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const gearimpact::SteadySweepRecord record = spec();
  std::vector<gearimpact::SweepPointResult> rows;
  try {
    rows = gearimpact::parse_sweep_csv(text, "sweep.csv", record);
  } catch (const gearimpact::InputError&) {
    return 0;
  }
  for (const gearimpact::SweepPointResult& r : rows) {
    const gearimpact::SteadyPoint& p = r.point;
    if (r.line < 0 || r.line >= record.lines || r.index < 0 || r.index >= record.points ||
        !std::isfinite(r.value_si) || !finite_or_absent(p.dte_mean_m) ||
        !finite_or_absent(p.dte_amplitude_m) || !finite_or_absent(p.dte_rms_m) ||
        !finite_or_absent(p.s_min_m) || !finite_or_absent(p.s_max_m) ||
        !finite_or_absent(p.dynamic_factor) || !finite_or_absent(p.impacts_drive_per_period) ||
        !finite_or_absent(p.impacts_coast_per_period)) {
      broken("a row outside the spec or not finite was read", text);
    }
  }
  const std::string written = gearimpact::sweep_csv(rows);
  const std::string rewritten =
      gearimpact::sweep_csv(gearimpact::parse_sweep_csv(written, "sweep.csv", record));
  if (rewritten != written) broken("the round trip changed the rows", written);
  return 0;
}
