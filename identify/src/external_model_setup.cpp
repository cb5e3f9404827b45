// Building a study's external model (make_external_model in external_model.hpp): every check
// that needs the template file, the study's variables or the program is made here, when the
// study is loaded, before any run.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>

#include "demfit/identify/external_model.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/template_text.hpp"

namespace demfit::identify {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kMaxTemplateBytes = std::size_t{4} << 20;
constexpr std::size_t kMaxCopiedFileBytes = std::size_t{64} << 20;
const std::string kExternalField = "study: model.external";

bool executable_file(const fs::path& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// command[0] as an absolute path: a name is looked up in $PATH (as a shell would, but without
// one); a path with '/' is taken relative to the study file's folder.
std::string resolve_program(const std::string& program, const fs::path& base_dir) {
  if (program.find('/') != std::string::npos) {
    const fs::path path = fs::path(program).is_absolute() ? fs::path(program) : base_dir / program;
    if (executable_file(path)) return fs::absolute(path).lexically_normal().string();
    throw std::runtime_error(kExternalField + ".command[0]: " + quote_path(path) +
                             " is not an executable file; check the path (relative to the study file) and its "
                             "execute permission");
  }
  const char* path_variable = std::getenv("PATH");
  std::stringstream folders(path_variable ? path_variable : "/usr/bin:/bin");
  for (std::string folder; std::getline(folders, folder, ':');) {
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / program;
    if (executable_file(candidate)) return fs::absolute(candidate).lexically_normal().string();
  }
  throw std::runtime_error(kExternalField + ".command[0]: program '" + printable(program) +
                           "' is not found in $PATH; install it, or give its path relative to the study file "
                           "(e.g. \"./solver.sh\")");
}

// Placeholders against declared parameters, declared parameters against the template and the study.
void check_parameters(const ExternalModelSpec& external, const std::string& text, const StudySpec& spec) {
  const std::string what = "template " + quote_path(external.template_file);
  std::set<std::string> used;
  for (const Placeholder& p : template_placeholders(text, kExternalField + ".template: " + what)) {
    if (!external.units.count(p.name))
      throw std::runtime_error(kExternalField + ".template: " + what + " line " + std::to_string(p.line) + ": {{" + p.name +
                               "}} is not a declared parameter; add \"" + p.name +
                               "\" with its unit to model.external.parameters, or correct the name");
    used.insert(p.name);
  }
  std::set<std::string> set_by_study;
  for (const auto& v : spec.variables) set_by_study.insert(v.name);
  for (const auto& [name, value] : spec.fixed_parameters) set_by_study.insert(name);
  std::set<std::string> candidate_parameters;  // at their off values unless the study sets them
  for (const auto& c : external.candidates) candidate_parameters.insert(c.parameter);
  for (const auto& [name, unit] : external.units) {
    if (!used.count(name))
      throw std::runtime_error(kExternalField + ".parameters." + name + ": the template " + quote_path(external.template_file) +
                               " never uses {{" + name + "}}; remove the parameter or place it in the template");
    if (!set_by_study.count(name) && !candidate_parameters.count(name))
      throw std::runtime_error(kExternalField + ".parameters." + name +
                               ": the study neither varies nor fixes it; add it to \"variables\" or to "
                               "model.fixed_parameters");
  }
  for (const auto& name : set_by_study)
    if (!external.units.count(name))
      throw std::runtime_error("study: '" + name +
                               "' is varied or fixed but is not a parameter of the external model; declare it in "
                               "model.external.parameters and use {{" + name + "}} in the template");
}

std::string read_study_file(const std::string& file, const fs::path& base_dir, const std::string& key,
                            std::size_t max_bytes) {
  const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : base_dir / file;
  try {
    return read_input_file(path, max_bytes, key + " " + quote_path(path));
  } catch (const std::exception& e) {
    throw std::runtime_error(kExternalField + "." + key + ": " + e.what());
  }
}

std::string read_template(const ExternalModelSpec& external, const fs::path& base_dir) {
  return read_study_file(external.template_file, base_dir, "template", kMaxTemplateBytes);
}

std::vector<std::string> read_files(const ExternalModelSpec& external, const fs::path& base_dir) {
  std::vector<std::string> out;
  for (const auto& f : external.files) out.push_back(read_study_file(f, base_dir, "files", kMaxCopiedFileBytes));
  return out;
}

}  // namespace

nlohmann::json resolved_external_model(const nlohmann::json& external, const fs::path& base_dir) {
  const ExternalModelSpec spec = parse_external_spec(external, kExternalField);
  return ExternalModel(spec, read_template(spec, base_dir), read_files(spec, base_dir), {}, {}, {}).fingerprint();
}

std::unique_ptr<ExternalModel> make_external_model(const StudySpec& spec, const fs::path& output_dir,
                                                   OutputKind output_kind) {
  if (!spec.experiments.empty())
    throw std::runtime_error("study: experiments: an external model is for a single-model study (\"model\" + "
                             "\"targets\"); give one study per external program");
  const ExternalModelSpec external = parse_external_spec(spec.model_overrides, kExternalField);
  std::string text = read_template(external, spec.base_dir);
  check_parameters(external, text, spec);
  std::string program = resolve_program(external.command[0], spec.base_dir);
  ParameterSet fixed = spec.fixed_parameters;
  for (const auto& c : external.candidates) {
    const bool varied = std::any_of(spec.variables.begin(), spec.variables.end(),
                                    [&](const VariableSpec& v) { return v.name == c.parameter; });
    if (!varied && !fixed.count(c.parameter)) fixed[c.parameter] = c.off_value;  // the base model: effect off
  }
  return std::make_unique<ExternalModel>(external, std::move(text), read_files(external, spec.base_dir),
                                         std::move(program), output_dir, std::move(fixed), output_kind);
}

}  // namespace demfit::identify
