// demfit: identify DEM contact parameters from measured curves.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/dem_core/memory_retention.hpp"
#include "demfit/dem_core/openmp_waiting.hpp"

namespace {

// The command path the user named ("demfit reproduce"), walked along argv's words (its own options
// and their values stepped over), and the first word after it that names no command or an option
// that belongs to one of its commands (both empty when there is none).
struct NamedCommand {
  const CLI::App* app = nullptr;
  std::string path = "demfit";
  std::string stray;
  std::string misplaced_option;  // an option written before the command it belongs to ("--jobs")
  std::string owner;             // that command ("table1")
};

// Of the commands that own a misplaced option, the first one named later on the line, else the first.
const CLI::App* owner_named_later(const std::vector<const CLI::App*>& owners, int from, int argc, char** argv) {
  for (int later = from; later < argc; ++later)
    for (const CLI::App* owner : owners)
      if (owner->check_name(argv[later])) return owner;
  return owners.front();
}

NamedCommand named_command(const CLI::App& root, int argc, char** argv) {
  NamedCommand named;
  named.app = &root;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word == "--") break;
    if (word[0] == '-') {  // an option of this command: step over it and its value
      const std::string name = word.substr(0, word.find('='));
      const CLI::Option* option = named.app->get_option_no_throw(name);
      if (option == nullptr) {  // "reproduce --jobs 2 table1": an option of the command that should follow
        const auto owners =
            named.app->get_subcommands([&](const CLI::App* sub) { return sub->get_option_no_throw(name) != nullptr; });
        if (!owners.empty()) {
          named.misplaced_option = name;
          named.owner = owner_named_later(owners, i + 1, argc, argv)->get_name();
        }
        break;
      }
      if (name == word && option->get_items_expected_max() > 0) ++i;
      continue;
    }
    const auto found = named.app->get_subcommands([&](const CLI::App* sub) { return sub->check_name(word); });
    if (found.empty()) {
      named.stray = word;
      break;
    }
    named.app = found.front();
    named.path += " " + word;
  }
  return named;
}

// A command-line mistake as one line naming it and the fix, exit status 1 like every other error
// (CLI11's own text spans two lines and exits 105-109). Help and --version keep CLI11's output.
int report_parse_error(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
  if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(error);
  const NamedCommand named = named_command(app, argc, argv);
  std::string message = error.what();
  const auto commands = named.app->get_subcommands([](const CLI::App*) { return true; });
  const bool command_missing = named.stray.empty() && dynamic_cast<const CLI::RequiredError*>(&error) != nullptr &&
                               named.app->get_subcommands().empty();
  if (!commands.empty() && (!named.stray.empty() || command_missing)) {
    message = named.stray.empty() ? "a command is required" : "unknown command '" + named.stray + "'";
    message += "; the commands are";
    for (const CLI::App* sub : commands) message += (sub == commands.front() ? " " : ", ") + sub->get_name();
  }
  // CLI11: "Could not convert: --jobs = 1e3" -> the option, the value and what it takes.
  const std::string unconverted = "Could not convert: ";
  if (dynamic_cast<const CLI::ConversionError*>(&error) != nullptr && message.rfind(unconverted, 0) == 0) {
    const std::string rest = message.substr(unconverted.size());
    const auto equals = rest.find(" = ");
    if (equals != std::string::npos)
      message = rest.substr(0, equals) + ": '" + rest.substr(equals + 3) +
                "' is not a number of the kind this option takes (a whole number for counts, e.g. 2; otherwise a "
                "decimal number with a point, e.g. 0.5, without a unit)";
  }
  if (!named.misplaced_option.empty())
    message = "option '" + named.misplaced_option + "' belongs after the command (e.g. '" + named.path + " " +
              named.owner + " " + named.misplaced_option + " ...')";
  // An argument may hold a newline or an escape sequence: one plain line, control characters escaped.
  std::cerr << "demfit: error: " << demfit::identify::printable(message) << "; see '" << named.path << " --help'\n";
  return 1;
}

// The one line printed for an error that reached main. Messages of demfit's own checks name the
// field and the fix; exceptions of the standard library or the JSON library that escaped them
// ("stod", "filesystem error: ...") are put in words naming the command and, where known, the
// file. Control and bidirectional characters of any echoed name are escaped (identify::printable).
std::string error_line(const std::string& command) {
  std::string message;
  try {
    throw;
  } catch (const std::filesystem::filesystem_error& e) {
    // what() is "filesystem error: <operation>: <reason> [path1] [path2]": the operation and the
    // reason, the paths escaped.
    std::string operation = e.what();
    const std::string prefix = "filesystem error: ";
    if (operation.rfind(prefix, 0) == 0) operation.erase(0, prefix.size());
    operation = operation.substr(0, operation.find(" ["));
    message = command + ": " + operation;
    if (!e.path1().empty()) message += " " + demfit::identify::quote_path(e.path1());
    message += e.path1().empty() && e.path2().empty()
                   ? "; check that the working folder still exists"
                   : "; check that the path exists and that you may read and write it";
  } catch (const nlohmann::json::exception& e) {
    message = command + ": a JSON value has the wrong type or is missing (" + e.what() +
              "); check the input files against docs/study_format.md and docs/cases.md";
  } catch (const std::invalid_argument& e) {
    message = command + ": a value is not a number (" + e.what() + "); check the numbers given on the command line " +
              "and in the input files";
  } catch (const std::out_of_range& e) {
    message = command + ": a value is out of range (" + e.what() + "); check the numbers given on the command " +
              "line and in the input files";
  } catch (const std::bad_alloc&) {
    message = command + ": out of memory; a count in the input (points, pixels, particles) is too large";
  } catch (const std::exception& e) { message = e.what(); } catch (...) {
    message = command + ": unknown error";
  }
  message = demfit::identify::printable(message);
  if (message.size() > 560) message = message.substr(0, 557) + "...";
  return message;
}

}  // namespace

int main(int argc, char** argv) {
  // Idle OpenMP threads spin briefly, then sleep (dem_core/openmp_waiting.hpp: measured between
  // passive and active waiting). libgomp reads this before main, hence a re-execution; the user's
  // OMP_WAIT_POLICY or GOMP_SPINCOUNT wins.
  demfit::dem_core::use_bounded_spin_waiting(argv);
  // Freed memory stays in the process: a rebuild's fresh pages cost ~10 us each on a virtual
  // machine (dem_core/memory_retention.hpp).
  demfit::dem_core::retain_freed_memory();
  CLI::App app{
      "demfit — identify Discrete Element Method contact parameters (NORMK, SHEARK, damping, "
      "friction) from measured curves.\nAll quantities are SI unless a name states its unit "
      "(e.g. volume_cm3, pressure_MPa)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "demfit " DEMFIT_VERSION " (commit " DEMFIT_COMMIT ")");
  demfit::apps::register_simulate(app);
  demfit::apps::register_identify(app);
  demfit::apps::register_reproduce(app);
  demfit::apps::register_diagnose(app);
  demfit::apps::register_target(app);
  demfit::apps::register_parameters(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) { return report_parse_error(app, e, argc, argv); } catch (...) {
    std::cerr << "demfit: error: " << error_line(named_command(app, argc, argv).path) << '\n';
    return 1;
  }
  return 0;
}
