// An external simulation program as a study model (external_model.hpp, docs/external-model.md).
#include "demfit/identify/external_model.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "demfit/identify/curve_io.hpp"
#include "demfit/identify/fnv_hash.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/template_text.hpp"
#include "timed_process.hpp"

namespace demfit::identify {
namespace fs = std::filesystem;

ExternalModel::ExternalModel(ExternalModelSpec spec, std::string template_text, std::vector<std::string> file_contents,
                             std::string program, fs::path output_dir, ParameterSet fixed, OutputKind output_kind)
    : spec_(std::move(spec)),
      template_text_(std::move(template_text)),
      file_contents_(std::move(file_contents)),
      program_(std::move(program)),
      output_dir_(std::move(output_dir)),
      fixed_(std::move(fixed)),
      output_kind_(output_kind) {}

std::vector<ParameterDescriptor> ExternalModel::parameters() const {
  std::vector<ParameterDescriptor> out;
  for (const auto& [name, unit] : spec_.units) {
    ParameterDescriptor d;
    d.name = name;
    d.unit = unit;
    const auto fixed = fixed_.find(name);
    if (fixed != fixed_.end()) d.default_value = fixed->second;
    out.push_back(d);
  }
  return out;
}

std::vector<CurveDescriptor> ExternalModel::curves() const {
  std::vector<CurveDescriptor> out;
  for (const auto& o : spec_.outputs) out.push_back({o.curve, o.x_column, o.y_column});
  return out;
}

nlohmann::json ExternalModel::fingerprint() const {
  // The template as lines: a changed template is then named by its first changed line.
  nlohmann::json lines = nlohmann::json::array();
  std::istringstream text(template_text_);
  for (std::string line; std::getline(text, line);) lines.push_back(line);
  nlohmann::json json = to_json(spec_);
  json.erase("time_limit_s");  // how long a run may take does not change what it computes
  json["template_lines"] = lines;
  nlohmann::json hashes = nlohmann::json::object();
  for (std::size_t i = 0; i < spec_.files.size() && i < file_contents_.size(); ++i) {
    char hex[24];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(file_contents_[i])));
    hashes[spec_.files[i]] = hex;
  }
  if (!spec_.files.empty()) json["files_fnv1a64"] = hashes;
  return {{"external", json}};
}

// A new folder per run: run-000001, run-000002, ... (mkdir is the claim, so concurrent runs and a
// resumed study never share one). The study's output folder is created with its marker when the
// first run comes before the study's own files (the initial-point check).
fs::path ExternalModel::fresh_run_folder() const {
  std::error_code error;
  if (!fs::exists(fs::symlink_status(output_dir_, error))) {
    fs::create_directories(output_dir_, error);
    if (error) throw std::runtime_error("cannot create " + quote_path(output_dir_) + ": " + error.message());
    mark_output_folder(output_dir_, output_kind_, {});
  }
  const fs::path runs = output_dir_ / kExternalRunsFolder;
  if (::mkdir(runs.c_str(), 0755) != 0 && errno != EEXIST)
    throw std::runtime_error("cannot create " + quote_path(runs) + ": " + std::strerror(errno));
  if (fs::is_symlink(fs::symlink_status(runs, error)) || !fs::is_directory(runs, error))
    throw std::runtime_error(quote_path(runs) + " is not a folder of its own (a link or a file); remove it");
  for (;;) {
    char name[32];
    std::snprintf(name, sizeof name, "run-%06ld", next_run_.fetch_add(1));
    const fs::path folder = runs / name;
    if (::mkdir(folder.c_str(), 0755) == 0) return folder;
    if (errno != EEXIST) throw std::runtime_error("cannot create " + quote_path(folder) + ": " + std::strerror(errno));
  }
}

// The curve the program wrote, from inside its run folder only: the file's real path (links
// resolved) must lie in the run folder's real path, so a link or ".." cannot lead a read outside.
Curve ExternalModel::read_output(const fs::path& run_folder, const ExternalOutput& output) const {
  std::error_code error;
  const fs::path real_folder = fs::canonical(run_folder, error);
  const fs::path file = run_folder / output.file;
  if (!fs::exists(fs::symlink_status(file, error)))
    throw std::runtime_error("wrote no " + quote_path(output.file) + " (curve '" + output.curve + "')");
  const fs::path real_file = fs::canonical(file, error);
  if (error) throw std::runtime_error(quote_path(output.file) + " cannot be resolved: " + error.message());
  const auto [folder_end, file_it] = std::mismatch(real_folder.begin(), real_folder.end(), real_file.begin(), real_file.end());
  if (folder_end != real_folder.end() || file_it == real_file.end())
    throw std::runtime_error(quote_path(output.file) + " leads outside the run folder (a symbolic link to " +
                             quote_path(real_file) + "); outputs are read only from inside the run folder");
  Curve curve = read_curve_csv(real_file, output.x_column, output.y_column);
  curve.x_label = output.x_column;
  curve.y_label = output.y_column;
  for (std::size_t i = 0; i < curve.x.size(); ++i)
    if (!std::isfinite(curve.x[i]) || !std::isfinite(curve.y[i]))
      throw std::runtime_error(quote_path(output.file) + " point " + std::to_string(i) + " is not finite (curve '" +
                               output.curve + "')");
  return curve;
}

CurveSet ExternalModel::evaluate(const ParameterSet& parameters, const EvaluationContext& context) const {
  ParameterSet values = fixed_;
  for (const auto& [name, value] : parameters) {
    if (!spec_.units.count(name))
      throw std::runtime_error("parameter '" + name + "' is not a parameter of the external model");
    values[name] = value;
  }
  const fs::path folder = fresh_run_folder();
  const std::string shown = quote_path(folder);
  try {
    write_file_atomically(folder / spec_.input_file,
                          substitute_template(template_text_, values, "template " + quote_path(spec_.template_file)));
    for (std::size_t i = 0; i < spec_.files.size(); ++i)
      write_file_atomically(path_inside(folder, fs::path(spec_.files[i]).filename().string()), file_contents_[i]);
    nlohmann::json record = {{"parameters", values}, {"command", spec_.command}};
    write_file_atomically(folder / "demfit_run.json", record.dump(2) + "\n");
    const auto result = detail::run_timed_process(program_, spec_.command, folder, spec_.time_limit_s,
                                                  {"OMP_NUM_THREADS=" + std::to_string(context.threads)});
    if (result.ending != detail::TimedProcessResult::Ending::exited || result.code != 0)
      throw std::runtime_error(detail::describe_ending(result, spec_.time_limit_s) + " (its output: stdout.txt, stderr.txt)");
    CurveSet curves;
    for (const auto& o : spec_.outputs) curves[o.curve] = read_output(folder, o);
    return curves;
  } catch (const std::exception& e) {
    throw std::runtime_error("external run " + shown + ": " + e.what());
  }
}

}  // namespace demfit::identify
