// The case reader's parts that the train file's reader (train_file.cpp) shares with the
// case file's (case_file.cpp): the file's name in problems (Reader), the TOML text's checks
// (parse_toml), a row's value and a two-gear case read from the tables. Private to lib/src/io.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <toml.hpp>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/case_file.hpp"

namespace gearimpact::case_reader {

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  // "file:line", the line when the value came from the text.
  std::string where(const toml::value* at) const {
    std::string where = file_;
    if (at != nullptr) {
      const toml::source_location location = at->location();
      // A value a --set wrote into the tables has no line of the file.
      if (!location.line_str().empty() && location.file_name() == file_) {
        where += ":" + std::to_string(location.line());
      }
    }
    return where;
  }

  // The problem at `at` (an InputError's problems keep their own wording).
  Problem problem(const std::string& field, const toml::value* at,
                  const std::string& message) const {
    Problem p;
    p.field = field;
    p.message = message;
    p.where = where(at);
    return p;
  }

  [[noreturn]] void fail(const std::string& field, const toml::value* at,
                         const std::string& message) const {
    throw CaseFileError(file_, {problem(field, at, message)});
  }

  // The problems of `e` at `at`.
  [[noreturn]] void fail(const toml::value* at, const InputError& e) const {
    std::vector<Problem> problems = e.problems();
    for (Problem& p : problems) p.where = where(at);
    throw CaseFileError(file_, std::move(problems));
  }

  const std::string& file() const { return file_; }

  [[noreturn]] void fail_at_line(std::size_t line, const std::string& message) const {
    throw CaseFileError(file_, "", file_ + ":" + std::to_string(line) + ": " + message);
  }

  [[noreturn]] void out_of_range(const std::string& field, const toml::value* at,
                                 const std::string& value, const std::string& allowed,
                                 const std::string& fix = {}) const {
    Problem p = range_problem(field, value, allowed, fix);
    p.where = where(at);
    throw CaseFileError(file_, {std::move(p)});
  }

 private:
  std::string file_;
};

// What a missing required key needs, for the message.
std::string expected_of(const Field& field);

// The SI values of a list row from a TOML array; each element checked against
// the row, errors naming section.key[i].
std::vector<double> read_list(const Reader& reader, const Field& field, const toml::value& value);

// The value of a non-text row as get() returns it; checked against the row.
double read_value(const Reader& reader, const Field& field, const toml::value& value);

// The case the tables of `root` give (a pair file or a run file), every problem of the file
// reported at once. Throws CaseFileError.
SimulationCase read_case(const Reader& reader, const toml::value& root, std::string_view file_name,
                         CaseFileKind kind);

// Parses the text to TOML, refusing what no case file can be. Throws CaseFileError.
toml::value parse_toml(const Reader& reader, std::string_view toml_text,
                       std::string_view file_name);

// The file's text, refused past the size of a case file. Throws CaseFileError.
std::string read_text(const std::filesystem::path& path);

}  // namespace gearimpact::case_reader
