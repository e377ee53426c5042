#include "shard_flag.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact::cli {

namespace {

// A whole number of at most 9 digits, for the shard's parts.
bool is_digits(const std::string& part) {
  return !part.empty() && part.size() <= 9 &&
         std::all_of(part.begin(), part.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

// SLURM's variable `name` as a whole number, or none when unset; throws InputError naming it
// when it is set but not one.
std::optional<long> slurm_number(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr) return std::nullopt;
  if (!is_digits(text)) {
    throw InputError(name, std::string("\"") + text + "\"",
                     "a whole number, as SLURM sets it for an array job");
  }
  return std::stol(text);
}

}  // namespace

ShardFlag parse_shard_flag(const std::string& text, bool given) {
  if (given && text.empty()) {
    throw InputError("--shard", "\"\"", "K/N with 0 <= K < N (leave --shard out to run all)");
  }
  std::string spec = text;
  if (spec.empty()) {
    const std::optional<long> id = slurm_number("SLURM_ARRAY_TASK_ID");
    const std::optional<long> count = slurm_number("SLURM_ARRAY_TASK_COUNT");
    const std::optional<long> min = slurm_number("SLURM_ARRAY_TASK_MIN");
    if (!id || !count) return {};
    spec = std::to_string(*id - min.value_or(0)) + "/" + std::to_string(*count);
  }
  // K/N: two runs of at most 9 digits around one slash.
  const std::size_t slash = spec.find('/');
  const auto digits = is_digits;
  const std::string k_text = slash == std::string::npos ? spec : spec.substr(0, slash);
  const std::string n_text = slash == std::string::npos ? "" : spec.substr(slash + 1);
  if (!digits(k_text) || !digits(n_text) || std::stoi(n_text) < 1 ||
      std::stoi(k_text) >= std::stoi(n_text)) {
    throw InputError("--shard", spec,
                     "K/N with 0 <= K < N (or SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT and "
                     "SLURM_ARRAY_TASK_MIN)");
  }
  return {std::stoi(k_text), std::stoi(n_text)};
}

}  // namespace gearimpact::cli
