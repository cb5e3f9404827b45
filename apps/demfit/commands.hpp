#pragma once
// Subcommand registration: each cmd_*.cpp adds its subcommands to the root CLI11 app.
// A subcommand's callback throws std::runtime_error with a one-line message on bad input;
// main() prints it as "demfit: error: <message>" and exits with status 1.
#include <CLI/CLI.hpp>

namespace demfit::apps {
void register_simulate(CLI::App& app);    // demfit simulate
void register_identify(CLI::App& app);    // demfit identify / report (and export, through register_export)
void register_export(CLI::App& app);      // demfit export --lsdyna | --liggghts
void register_reproduce(CLI::App& app);   // demfit reproduce table1|table2|table3|figures|all
void register_diagnose(CLI::App& app);    // demfit diagnose
void register_target(CLI::App& app);      // demfit target from-image, target compare
void register_parameters(CLI::App& app);  // demfit parameters
}  // namespace demfit::apps
