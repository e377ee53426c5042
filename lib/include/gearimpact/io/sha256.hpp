// SHA-256 (FIPS 180-4) of bytes, as lowercase hex: the digest of every data-set record and of the
// spec, the same as `sha256sum` prints, so that a user can check a file without this program.
#pragma once

#include <string>
#include <string_view>

namespace gearimpact {

std::string sha256_hex(std::string_view bytes);

}  // namespace gearimpact
