// libFuzzer target for the case-file reader. The contract under test: any
// bytes give either a SimulationCase or a CaseFileError, never a crash, hang,
// other exception or sanitizer report; and a case that is read writes back to
// text that reads to the same case (write -> read -> write is a fixed point).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "gearimpact/io/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  gearimpact::SimulationCase simulation_case;
  try {
    simulation_case = gearimpact::parse_case(text, "fuzz.toml");
  } catch (const gearimpact::CaseFileError&) {
    return 0;
  }
  for (gearimpact::CaseUnits units : {gearimpact::CaseUnits::readable, gearimpact::CaseUnits::si}) {
    const std::string written = gearimpact::write_case_file(simulation_case, units);
    const std::string rewritten =
        gearimpact::write_case_file(gearimpact::parse_case(written, "fuzz.toml"), units);
    if (rewritten != written) {
      std::fprintf(stderr, "round trip changed the case:\n%s\n---\n%s\n", written.c_str(),
                   rewritten.c_str());
      std::abort();
    }
  }
  return 0;
}
