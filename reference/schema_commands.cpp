#include <cstdio>
#include <memory>
#include <string>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/case/schema.hpp"

namespace gearimpact::cli {

namespace {

// The flags that set case keys, as a Markdown table.
std::string flags_markdown() {
  std::string table = "| flag | key | commands |\n|---|---|---|\n";
  for (const CaseFlag& flag : kCaseFlags) {
    std::string key = "`" + std::string(flag.key) + "`";
    if (flag.switch_value != nullptr) key += " = \"" + std::string(flag.switch_value) + "\"";
    table += "| `" + std::string(flag.flag) + "` | " + key + " | " + command_names(flag.commands) +
             " |\n";
  }
  return table;
}

}  // namespace

void register_schema_commands(CLI::App& app) {
  auto flags = std::make_shared<bool>(false);
  CLI::App* schema = app.add_subcommand(
      "schema",
      "print every case-file key as a Markdown table: unit, default, allowed range, meaning (the "
      "table of docs/case-files.md)");
  schema->add_flag("--flags", *flags,
                   "print instead the command-line flags that set case keys, and the keys they "
                   "set");
  schema->callback(
      [flags] { std::fputs((*flags ? flags_markdown() : schema_markdown()).c_str(), stdout); });
}

}  // namespace gearimpact::cli
