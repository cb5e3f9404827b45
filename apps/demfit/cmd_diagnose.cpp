// Placeholder until its module lands: the subcommand exists and says it is not built yet.
#include <stdexcept>
#include "commands.hpp"

namespace demfit::apps {
void register_diagnose(CLI::App& app) {
  auto* cmd = app.add_subcommand("diagnose", "(not available in this build yet)");
  cmd->allow_extras();
  cmd->callback([] { throw std::runtime_error("'diagnose' is not implemented in this build yet"); });
}
}  // namespace demfit::apps
