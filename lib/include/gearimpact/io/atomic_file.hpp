// Writing an output file so that a reader never sees half of it.
#pragma once

#include <string>
#include <string_view>

namespace gearimpact {

// Writes `text` to a temporary file in the directory of `path`, then renames it
// onto `path`. Throws std::runtime_error naming the path on any failure.
void write_file_atomically(const std::string& path, std::string_view text);

}  // namespace gearimpact
