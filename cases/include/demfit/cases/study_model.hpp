#pragma once
// What a study simulates, as every front end that runs a study needs it (the Python module;
// the command line's identify spells the same rules): the model with the derived curves of
// relative-axis targets, the resolved model recorded in the store (a resumed study must
// simulate the same thing), and the input files no output may replace.
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/model.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::cases {

// make_study_model (built-in cases, case files, the "analytic" test model) or, for
// "model": {"external": ...}, the external program (identify/external_model.hpp), whose runs go in
// folders under `output_dir`; wrapped in identify::RelativeAxisModel when a target's curve is on a
// relative axis ("pressure_volume@strain", identify/relative_axis.hpp). Throws std::runtime_error.
std::unique_ptr<identify::Model> make_identify_model(const identify::StudySpec& spec,
                                                     const std::filesystem::path& output_dir);

// The model of a study's cheap level (identify::cheap_level_study; identify::RunOptions::cheap_model),
// an external program's runs in output_dir/cheap_level; nullptr when the study declares none.
std::unique_ptr<identify::Model> make_cheap_level_model(const identify::StudySpec& spec,
                                                        const std::filesystem::path& output_dir);

// The resolved model of a study (identify::RunOptions::resolved_model): {"analytic": overrides}
// for the analytic model, the case with every default filled in for a DEM case, the external
// program's fingerprint (template, command, outputs, files) for an external model, and for an
// experiments study one such object per experiment, keyed by the experiment's name.
nlohmann::json resolved_study_model(const identify::StudySpec& spec);

// The study file, its target CSV files and its case file (when the model names a file).
std::vector<std::filesystem::path> study_input_files(const identify::StudySpec& spec,
                                                     const std::filesystem::path& study_file);

// A study file run on this machine's threads (identify::ThreadPoolEvaluator, options.jobs x
// options.threads_per_job), every configuration error before anything is created: the study,
// the output-folder rules and the lock (identify::claim_study_folder with `resume_hint`), the
// model, one evaluation at the initial point (identify::preflight_study; on a resume whose store
// holds that run, its stored curves instead), then the loop.
// `out_option` names the output option in errors ("--out", "out"). options.output_dir must be set.
// `parsed` is identify::load_study_file(study_file), read once by the caller.
identify::StudyResult run_study_file(const identify::StudySpec& parsed, const std::filesystem::path& study_file,
                                     identify::RunOptions options, std::string_view resume_hint,
                                     std::string_view out_option);

}  // namespace demfit::cases
