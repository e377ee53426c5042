// [[faults]] in case files (fault_schema, case_file.cpp; docs/faults.md): read,
// written back and read again to the same case, part of case_key, and every
// fault that does not fit refused with its key, its line and its range.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/io/case_file.hpp"

using namespace gearimpact;

namespace {

std::string paper_case1() {
  std::ifstream in(std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / "case1.toml");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The message of parsing case 1 with `tail` appended, or "" when it reads.
std::string refusal(const std::string& tail) {
  try {
    parse_case(paper_case1() + tail, "f.toml");
  } catch (const CaseFileError& e) {
    return e.what();
  }
  return {};
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("faults read, write back and enter the case key") {
  const std::string tail = R"(
[[faults]]
gear = "pinion"
tooth = 3
kind = "root-crack"
depth = "0.8 mm"
angle = "45 deg"

[[faults]]
gear = "wheel"
tooth = 79
kind = "missing"

[[faults]]
gear = "pinion"
tooth = 4
kind = "root-crack"
depth = "0.2 mm"
angle = "30 deg"
profile = "full-width"
end_depth = "0.6 mm"
)";
  const SimulationCase c = parse_case(paper_case1() + tail, "f.toml");
  REQUIRE(c.faults.size() == 3);
  CHECK(c.faults[0].gear == Gear::one);
  CHECK(c.faults[0].tooth == 3);
  CHECK(c.faults[0].state.kind == ToothKind::root_crack);
  CHECK(c.faults[0].state.crack.depth_m == 0.8e-3);
  CHECK(std::fabs(c.faults[0].state.crack.angle_rad - pi / 4) < 1e-15);
  CHECK(c.faults[1].gear == Gear::two);
  CHECK(c.faults[1].state.kind == ToothKind::missing);
  CHECK(c.faults[2].state.crack.profile == CrackProfile::full_width);
  CHECK(c.faults[2].state.crack.end_depth_m == 0.6e-3);
  // Written back in SI and in readable units, read again to the same faults.
  for (CaseUnits units : {CaseUnits::si, CaseUnits::readable}) {
    const SimulationCase again = parse_case(write_case_file(c, units), "g.toml");
    CHECK(again.faults == c.faults);
    CHECK(case_key(again) == case_key(c));
  }
  SimulationCase healthy = c;
  healthy.faults.clear();
  CHECK(case_key(healthy) != case_key(c));
  CHECK(has(case_key(c), "faults[2].end_depth="));
}

TEST_CASE("faults that do not fit are refused, naming the key and its range") {
  SUBCASE("a tooth the gear does not have") {
    const std::string m =
        refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 25\nkind = \"missing\"\n");
    CHECK(has(m, "faults[0].tooth"));
    CHECK(has(m, "0 ... 19"));
    // At the line of the key: case1.toml's lines, a blank one, [[faults]], gear, tooth.
    const std::string base = paper_case1();
    const auto lines = std::count(base.begin(), base.end(), '\n');
    CHECK(has(m, "f.toml:" + std::to_string(lines + 4)));
  }
  SUBCASE("a crack past the centre line: q sin nu >= h_c") {
    const std::string m = refusal(
        "\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"root-crack\"\ndepth = \"3 mm\"\n"
        "angle = \"90 deg\"\n");
    CHECK(has(m, "faults[0].depth"));
    CHECK(has(m, "q sin nu < h_c"));
  }
  SUBCASE("two faults on one tooth") {
    const std::string m = refusal(
        "\n[[faults]]\ngear = \"wheel\"\ntooth = 7\nkind = \"missing\"\n"
        "\n[[faults]]\ngear = \"wheel\"\ntooth = 7\nkind = \"root-crack\"\ndepth = \"0.1 mm\"\n"
        "angle = \"45 deg\"\n");
    CHECK(has(m, "faults[1].tooth"));
    CHECK(has(m, "faults[0] is on it already"));
  }
  SUBCASE("faults with a constant mesh stiffness") {
    std::string text = paper_case1();
    text.replace(text.find("[model]\n"), 8,
                 "[model]\nmesh_stiffness = \"constant\"\nconstant_mesh_stiffness = \"3e8 N/m\"\n");
    std::string m;
    try {
      parse_case(text + "\n[[faults]]\ngear = \"pinion\"\ntooth = 1\nkind = \"missing\"\n",
                 "f.toml");
    } catch (const CaseFileError& e) {
      m = e.what();
    }
    CHECK(has(m, "model.mesh_stiffness"));
    CHECK(has(m, "\"time-varying\""));
  }
  SUBCASE("an angle outside (0, 90] deg, a key a missing tooth does not use, an unknown key") {
    CHECK(has(refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"root-crack\"\n"
                      "depth = \"0.1 mm\"\nangle = \"95 deg\"\n"),
              "faults[0].angle"));
    CHECK(has(refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"missing\"\n"
                      "depth = \"0.1 mm\"\n"),
              "faults[0].depth"));
    CHECK(has(refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"missing\"\n"
                      "dept = \"0.1 mm\"\n"),
              "unknown key faults[0].dept"));
    CHECK(has(refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"root-crack\"\n"),
              "faults[0].depth is missing"));
  }
}
