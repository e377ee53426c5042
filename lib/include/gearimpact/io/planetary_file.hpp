// A planetary file (docs/planetary.md, A planetary file): an optional name and
// a [planetary] section whose keys, one row each of planetary_schema(), give
// the linear stage's PlanetaryParameters. `gearimpact modes` reads it.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "gearimpact/modes/planetary.hpp"

namespace gearimpact {

struct PlanetaryCase {
  std::string name;  // the file's `name`, else its stem
  PlanetaryParameters parameters;
};

// True when the TOML text has a [planetary] section. Throws CaseFileError for
// text that is no TOML (as the case reader refuses it).
bool is_planetary_text(std::string_view toml_text, std::string_view file_name);
bool is_planetary_file(const std::filesystem::path& path);

// The stage of the text, every problem of the file reported at once, each
// naming its key as planetary.KEY with its allowed range: an unknown key or
// section, a missing required key, a value outside its row, planet_angles
// of another count than `planets`, and what planetary_model refuses (angles
// not increasing from 0). Throws CaseFileError.
PlanetaryCase parse_planetary(std::string_view toml_text, std::string_view file_name);
PlanetaryCase read_planetary_file(const std::filesystem::path& path);

}  // namespace gearimpact
