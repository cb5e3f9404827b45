#pragma once
// Any simulation program as a study model ("model": {"external": {...}} in a study file;
// docs/external-model.md). Each evaluation gets a fresh run folder inside the study's output
// folder, an input file written from the template with the parameter values, one run of the
// command (argument vector, no shell, wall-time limit), and the curves read back from the CSV
// files the program wrote there. A failed, timed-out or output-less run is a failed evaluation
// (std::runtime_error), which the study loop records and skips.
#include <atomic>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/model.hpp"
#include "demfit/identify/safe_output.hpp"

namespace demfit::identify {

struct StudySpec;

// StudySpec::model_reference of a study whose model is an external program; its model_overrides
// is then the checked "external" object (to_json of ExternalModelSpec).
inline constexpr const char* kExternalModelReference = "external";

// One curve the program writes: CSV `file` (relative to the run folder) with columns x and y,
// whose labels carry the units ("time_s", "torque_Nm").
struct ExternalOutput {
  std::string curve;
  std::string file;
  std::string x_column;
  std::string y_column;
};

// A candidate effect for `demfit diagnose` (docs/external-model.md "Candidate effects"): one
// template parameter with the value at which the effect vanishes (`off`, inside [lower, upper]),
// in the parameter's declared unit. Unless the study varies or fixes the parameter, the base model
// runs with it at `off`.
struct ExternalCandidate {
  std::string name;         // effect name in reports ("cohesion"); unique
  std::string description;  // one line (default: "<parameter> from <off> (off)")
  std::string parameter;    // a declared template parameter
  double off_value = 0.0;
  double lower = 0.0, upper = 0.0;  // fitting range, lower < upper, finite
  std::vector<std::string> curves;  // outputs it changes; empty = all
};

// The "external" object of a study's model, checked for form (parse_external_spec) but not yet
// against the template file or the study's variables (make_external_model).
struct ExternalModelSpec {
  std::vector<std::string> command;          // argv; command[0] a program in $PATH or a path
  std::string template_file;                 // relative to the study file
  std::string input_file;                    // file name written into each run folder
  std::map<std::string, std::string> units;  // declared parameters: name -> unit ("-" = dimensionless)
  double time_limit_s = 0.0;                 // [s] wall time of one run
  std::vector<ExternalOutput> outputs;
  // Files copied into each run folder under their own names (meshes, data files), relative to
  // the study file.
  std::vector<std::string> files;
  std::vector<ExternalCandidate> candidates;  // for demfit diagnose; none = none declared
};

// Reads and checks the "external" object; errors name `field` ("study: model.external") and the fix.
ExternalModelSpec parse_external_spec(const nlohmann::json& json, const std::string& field);
nlohmann::json to_json(const ExternalModelSpec& spec);

class ExternalModel final : public Model {
 public:
  // `template_text` is the template's content; `program` the resolved path of command[0];
  // `runs_dir` the folder under which run folders are made; `output_dir` the study's output
  // folder (runs_dir is inside it; created with its marker if the first run comes before the
  // study's own files).
  // `file_contents` holds the content of each spec.files entry, in its order.
  ExternalModel(ExternalModelSpec spec, std::string template_text, std::vector<std::string> file_contents,
                std::string program, std::filesystem::path output_dir, ParameterSet fixed,
                OutputKind output_kind = OutputKind::identify);
  std::vector<ParameterDescriptor> parameters() const override;
  std::vector<CurveDescriptor> curves() const override;
  ParameterSet default_parameters() const override { return fixed_; }
  CurveSet evaluate(const ParameterSet& parameters, const EvaluationContext& context) const override;
  // What --resume compares: command, template lines, input name, parameters, outputs and the
  // copied files' content (as a hash).
  nlohmann::json fingerprint() const;

 private:
  std::filesystem::path fresh_run_folder() const;
  Curve read_output(const std::filesystem::path& run_folder, const ExternalOutput& output) const;

  ExternalModelSpec spec_;
  std::string template_text_;
  std::vector<std::string> file_contents_;
  std::string program_;
  std::filesystem::path output_dir_;
  ParameterSet fixed_;
  OutputKind output_kind_ = OutputKind::identify;  // marker of an output folder the first run creates
  mutable std::atomic<long> next_run_{1};
};

// The study's external model: reads the template (relative to spec.base_dir), refuses a
// placeholder that is not a declared parameter, a declared parameter the template never uses or
// the study neither varies nor fixes (a candidate's parameter runs at its off value unless the
// study sets it), a variable that is not declared, and a command[0] that is not an executable
// program. Run folders go to output_dir/external_runs; `output_kind` marks output_dir when the
// first run creates it (identify, or diagnose for demfit diagnose).
std::unique_ptr<ExternalModel> make_external_model(const StudySpec& spec, const std::filesystem::path& output_dir,
                                                   OutputKind output_kind = OutputKind::identify);

// What --resume compares for an external model ("external" object of a study's model, read
// against base_dir): the model's fingerprint(), from the template file as it is now.
nlohmann::json resolved_external_model(const nlohmann::json& external, const std::filesystem::path& base_dir);

// Folder of the run folders inside a study's output folder.
inline constexpr const char* kExternalRunsFolder = "external_runs";

}  // namespace demfit::identify
