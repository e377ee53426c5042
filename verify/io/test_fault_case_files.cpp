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

namespace {

const std::string kSpall = R"(
[[faults]]
gear = "pinion"
tooth = 2
kind = "spall"
depth = "0.2 mm"
width = "4 mm"
start_radius = "20 mm"
end_radius = "21 mm"
)";

// kSpall with one line replaced: `key = ...` by `line`.
std::string spall_with(const std::string& key, const std::string& line) {
  std::string text = kSpall;
  const std::size_t at = text.find("\n" + key + " = ");
  text.replace(at + 1, text.find('\n', at + 1) - at - 1, line);
  return text;
}

}  // namespace

TEST_CASE("a spall and a chipped tip read, write back and enter the case key") {
  const std::string tail = kSpall + R"(flank = "coast"

[[faults]]
gear = "wheel"
tooth = 5
kind = "tip-chip"
radius = "81.5 mm"
width = "5 mm"
)";
  const SimulationCase c = parse_case(paper_case1() + tail, "f.toml");
  REQUIRE(c.faults.size() == 2);
  const Spall& spall = c.faults[0].state.spall;
  CHECK(c.faults[0].state.kind == ToothKind::spall);
  CHECK(spall.depth_m == 0.2e-3);
  CHECK(spall.width_m == 4e-3);
  CHECK(spall.start_radius_m == 20e-3);
  CHECK(spall.end_radius_m == 21e-3);
  CHECK(spall.flank == CrackFlank::unloaded);
  CHECK(c.faults[1].state.kind == ToothKind::tip_chip);
  CHECK(c.faults[1].state.chip.radius_m == 81.5e-3);
  CHECK(c.faults[1].state.chip.width_m == 5e-3);
  for (CaseUnits units : {CaseUnits::si, CaseUnits::readable}) {
    const SimulationCase again = parse_case(write_case_file(c, units), "g.toml");
    CHECK(again.faults == c.faults);
    CHECK(case_key(again) == case_key(c));
  }
  CHECK(has(case_key(c), "faults[0].end_radius="));
  CHECK(has(case_key(c), "faults[1].radius="));
  // The drive flank is the default.
  const SimulationCase drive = parse_case(paper_case1() + kSpall, "f.toml");
  CHECK(drive.faults[0].state.spall.flank == CrackFlank::loaded);
}

TEST_CASE("a spall or a chip that does not fit is refused, naming the key and its limit in mm") {
  SUBCASE("an unknown kind lists the kinds") {
    const std::string m = refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"pit\"\n");
    CHECK(has(m, "faults[0].kind"));
    CHECK(has(m, "\"root-crack\", \"missing\", \"spall\", \"tip-chip\""));
  }
  SUBCASE("each key's range") {
    CHECK(has(refusal(spall_with("depth", "depth = \"-0.1 mm\"")), "faults[0].depth"));
    CHECK(has(refusal(spall_with("width", "width = \"0 mm\"")), "faults[0].width"));
    CHECK(has(refusal(spall_with("start_radius", "start_radius = \"-1 mm\"")),
              "faults[0].start_radius"));
    const std::string flank = refusal(kSpall + "flank = \"left\"\n");
    CHECK(has(flank, "faults[0].flank"));
    CHECK(has(flank, "\"drive\", \"coast\""));
    CHECK(has(refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"tip-chip\"\n"
                      "radius = \"21 mm\"\nwidth = \"-2 mm\"\n"),
              "faults[0].width"));
  }
  SUBCASE("a spall off the active profile") {
    // The pinion's base circle is 18.79 mm, its tip 22 mm; the wheel's tip
    // meets its flank at 18.85 mm (X_start = lp - sqrt(82^2 - 75.18^2) mm).
    const std::string low = refusal(spall_with("start_radius", "start_radius = \"18.82 mm\""));
    CHECK(has(low, "faults[0].start_radius"));
    CHECK(has(low, "on the active profile of the pinion tooth"));
    CHECK(has(low, "22 mm"));
    const std::string high = refusal(spall_with("end_radius", "end_radius = \"22.5 mm\""));
    CHECK(has(high, "faults[0].end_radius"));
    CHECK(has(high, "(20 mm, 22 mm]"));
    CHECK(has(refusal(spall_with("end_radius", "end_radius = \"19.5 mm\"")), "above start_radius"));
  }
  SUBCASE("a pit deeper than the tooth's half thickness") {
    const std::string m = refusal(spall_with("depth", "depth = \"1.5 mm\""));
    CHECK(has(m, "faults[0].depth"));
    CHECK(has(m, "the half thickness of the pinion tooth at r = 21 mm"));
    CHECK(has(m, " mm, the thinner end"));
    CHECK(refusal(spall_with("depth", "depth = \"0.9 mm\"")).empty());
  }
  SUBCASE("wider than the face") {
    const std::string m = refusal(spall_with("width", "width = \"11 mm\""));
    CHECK(has(m, "faults[0].width"));
    CHECK(has(m, "at most the face width b = 10 mm"));
    const std::string chip = refusal(
        "\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"tip-chip\"\n"
        "radius = \"21 mm\"\nwidth = \"10.5 mm\"\n");
    CHECK(has(chip, "faults[0].width"));
    // Across the whole face is read: the pair has no contact over the fault's extent.
    CHECK(refusal(spall_with("width", "width = \"10 mm\"")).empty());
    CHECK(refusal("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"tip-chip\"\n"
                  "radius = \"21 mm\"\nwidth = \"10 mm\"\n")
              .empty());
  }
  SUBCASE("a chip radius beyond the tip or below the base circle") {
    for (const char* r : {"22.5 mm", "18 mm"}) {
      const std::string m =
          refusal(std::string("\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"tip-chip\"\n"
                              "radius = \"") +
                  r + "\"\nwidth = \"2 mm\"\n");
      CHECK(has(m, "faults[0].radius"));
      CHECK(has(m, "22 mm]: above the base circle"));
    }
  }
  SUBCASE("keys of another kind") {
    const std::string radius = refusal(kSpall + "radius = \"21 mm\"\n");
    CHECK(has(radius, "faults[0].radius = \"21 mm\" is read only with kind = \"tip-chip\""));
    const std::string angle = refusal(kSpall + "angle = \"45 deg\"\n");
    CHECK(has(angle, "is read only with kind = \"root-crack\""));
    const std::string depth = refusal(
        "\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"tip-chip\"\nradius = \"21 mm\"\n"
        "width = \"2 mm\"\ndepth = \"0.1 mm\"\n");
    CHECK(has(depth,
              "faults[0].depth = \"0.1 mm\" is read only with kind = \"root-crack\" or "
              "\"spall\""));
    // One message for the key, not one per row that has it.
    CHECK(depth.find("faults[0].depth") == depth.rfind("faults[0].depth"));
    const std::string width = refusal(
        "\n[[faults]]\ngear = \"pinion\"\ntooth = 0\n"
        "kind = \"missing\"\nwidth = \"2 mm\"\n");
    CHECK(has(width,
              "is read only with profile = \"partial-width\", or kind = \"spall\" or "
              "\"tip-chip\""));
  }
}
