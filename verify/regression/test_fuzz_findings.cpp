// What the fuzzer found stays found: every input of fuzz/corpus/case_file/
// whose name starts with "crash-" (an input that once crashed the reader) or
// "broken-" (a hand-made bad file) is refused by parse_case with a
// CaseFileError naming the file, never a crash, a hang or another exception.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gearimpact/io/case_file.hpp"

using namespace gearimpact;

TEST_CASE("every crash- and broken- input of the fuzz corpus is a CaseFileError") {
  const std::filesystem::path corpus = GEARIMPACT_FUZZ_CORPUS_DIR;
  int crashes = 0;
  int broken = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    const std::string name = entry.path().filename().string();
    const bool crash = name.rfind("crash-", 0) == 0;
    if (!crash && name.rfind("broken-", 0) != 0) continue;
    CAPTURE(name);
    std::ifstream stream(entry.path(), std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(stream),
                           std::istreambuf_iterator<char>()};
    bool refused = false;
    try {
      parse_case(text, name);
    } catch (const CaseFileError& e) {
      refused = true;
      CHECK(e.file() == name);
      CHECK(std::string(e.what()).rfind(name, 0) == 0);
    }
    CHECK(refused);
    ++(crash ? crashes : broken);
  }
  // The corpus holds one finding of the fuzzer (toml11's out-of-bounds read
  // on invalid UTF-8 in a literal string) and eight hand-made bad files.
  CHECK(crashes >= 1);
  CHECK(broken >= 8);
}
