// A TOML value in a message, as the case reader and the data-set spec's reader both name it: its
// type in words, and its text as the file wrote it.
#pragma once

#include <string>
#include <toml.hpp>

namespace gearimpact {

// "a boolean", "an integer", "a float", "a string", "an array", "a table", "nothing", or
// "a date or time".
std::string toml_type_name(const toml::value& value);

// The value as the file wrote it: a string quoted, a number, a boolean, an array's elements; the
// type in parentheses for anything else.
std::string toml_written(const toml::value& value);

}  // namespace gearimpact
