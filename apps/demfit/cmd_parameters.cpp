// demfit parameters: prints the model-parameter table (cases/parameter_table.hpp) as Markdown.
// docs/parameters.md is this output; a test keeps the two equal.
#include <iostream>

#include "commands.hpp"
#include "demfit/cases/parameter_table.hpp"

namespace demfit::apps {

void register_parameters(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "parameters",
      "Print the model parameters as a Markdown table: name, unit, valid range, default, effect off value,\n"
      "where it lives, contact laws, LS-DYNA card and field, case-file field, meaning (docs/parameters.md).");
  cmd->callback([] { std::cout << cases::parameters_markdown(); });
}

}  // namespace demfit::apps
