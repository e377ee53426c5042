#include "data_location.hpp"

#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace gearimpact::cli {

namespace {

// A file every paper_data folder has; a folder without it is not one.
constexpr const char* kMarker = "dynamics_statements.csv";

bool holds_paper_data(const std::filesystem::path& dir) {
  std::error_code error;
  return std::filesystem::is_regular_file(dir / kMarker, error);
}

std::filesystem::path checked(const std::filesystem::path& dir, const std::string& given_by) {
  if (!holds_paper_data(dir)) {
    throw std::runtime_error("no paper data in " + dir.string() + " (" + given_by +
                             "): " + kMarker + " is missing there");
  }
  return dir;
}

}  // namespace

std::filesystem::path paper_data_dir(const std::string& flag_value) {
  if (!flag_value.empty()) return checked(flag_value, "--paper-data");
  const char* from_environment = std::getenv("GEARIMPACT_PAPER_DATA");
  if (from_environment != nullptr && *from_environment != '\0') {
    return checked(from_environment, "GEARIMPACT_PAPER_DATA");
  }
  // Linux names the running program in /proc; elsewhere the flag or the
  // environment variable says where the data is.
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) {
    throw std::runtime_error(
        "cannot tell where the program is (/proc/self/exe: " + error.message() +
        ") to find the paper data beside it; give --paper-data DIR or set GEARIMPACT_PAPER_DATA");
  }
  const std::filesystem::path beside =
      (program.parent_path().parent_path() / "share" / "gearimpact" / "paper_data")
          .lexically_normal();
  if (!holds_paper_data(beside)) {
    throw std::runtime_error("no paper data beside the program " + program.string() +
                             ": looked for " + (beside / kMarker).string() +
                             "; give --paper-data DIR or set GEARIMPACT_PAPER_DATA");
  }
  return beside;
}

}  // namespace gearimpact::cli
