// demfit export: the study's answer written for another DEM code, as LS-DYNA cards (--lsdyna,
// identify/lsdyna_export.hpp) or LIGGGHTS input lines (--liggghts, cases/liggghts_export.hpp).
// Both follow the same file rules: a new regular file, --force replaces a regular file only,
// - writes to standard output; the answer is study_answer.hpp's, as in report.md.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "demfit/cases/liggghts_export.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/lsdyna_export.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_answer.hpp"
#include "demfit/identify/study_store.hpp"

namespace demfit::apps {
namespace {

// The comment lines of an export: the 95 % intervals and identifiability of the identified
// values, and the material context that NORMK and SHEARK are relative to.
std::vector<std::string> export_comments(const identify::StudyStore& store, const nlohmann::json& study,
                                         const std::filesystem::path& db) {
  std::vector<std::string> lines;
  const auto result = store.result();
  const nlohmann::json uncertainty = result ? result->value("uncertainty", nlohmann::json()) : nlohmann::json();
  for (const auto& v : study.value("variables", nlohmann::json::array())) {
    const std::string name = v.value("name", std::string("?"));
    std::string line = "variable " + name + ": bounds [" + identify::json_excerpt(v.value("lower", nlohmann::json())) +
                       ", " + identify::json_excerpt(v.value("upper", nlohmann::json())) + "]";
    const nlohmann::json value =
        result ? result->value("best_parameters", nlohmann::json::object()).value(name, nlohmann::json())
               : nlohmann::json();
    if (uncertainty.is_object() && value.is_number()) {
      // The same interval as report.md and best_parameters.json (reported_interval.hpp).
      const identify::ReportedInterval interval = identify::reported_interval(uncertainty, name, value.get<double>());
      line += ", 95 % interval " + identify::interval_text(interval);
      line += interval.identifiable ? ", identifiable" : ", NOT identifiable from these targets";
    } else {
      line += ", no interval (study not finished)";
    }
    lines.push_back(line);
  }
  try {
    const auto& model = study.at("model");
    const cases::CaseSpec c =
        cases::resolve_case(model.at("case").get<std::string>(), model.value("overrides", nlohmann::json::object()),
                            std::filesystem::absolute(db).parent_path());
    char text[240];
    std::snprintf(text, sizeof text,
                  "material context: E = %.6g Pa, nu = %.4g, K = E/(3(1-2nu)) = %.6g Pa, radius = %.6g m, "
                  "density = %.6g kg/m3 (NORMK is relative to K R)",
                  c.material.youngs_modulus, c.material.poisson_ratio, c.material.bulk_modulus(), c.material.radius,
                  c.material.density);
    lines.push_back(text);
  } catch (const std::exception& e) {
    lines.push_back(std::string("material context: case not available here (") + e.what() + ")");
  }
  return lines;
}

// The export formats: the option that names the file, what the file is, and its usual name.
struct ExportFormat {
  const char* option;  // "--lsdyna"
  const char* what;    // "keyword file"
  const char* example;  // "out.k"
};
constexpr ExportFormat kLsdynaFormat{"--lsdyna", "LS-DYNA keyword file", "a new .k file"};
constexpr ExportFormat kLiggghtsFormat{"--liggghts", "LIGGGHTS input file", "a new .in file"};

// The study's variables with the answer's values and intervals, as report.md shows them
// (reported_interval.hpp); no interval when the study has not finished.
cases::IdentifiedVariables identified_variables(const identify::StudyStore& store, const nlohmann::json& study,
                                                const identify::ParameterSet& answer) {
  cases::IdentifiedVariables out;
  const auto result = store.result();
  const nlohmann::json uncertainty = result ? result->value("uncertainty", nlohmann::json()) : nlohmann::json();
  for (const auto& v : study.value("variables", nlohmann::json::array())) {
    const std::string name = v.value("name", std::string());
    const auto value = answer.find(name);
    if (name.empty() || value == answer.end()) continue;
    identify::ReportedInterval interval;
    if (result && uncertainty.is_object()) interval = identify::reported_interval(uncertainty, name, value->second);
    interval.value = value->second;
    out[name] = interval;
  }
  return out;
}

// The case the study simulated: the resolved case its store recorded, else the study's case
// reference resolved beside the store.
cases::CaseSpec study_case(const identify::StudyStore& store, const nlohmann::json& study,
                           const std::filesystem::path& db) {
  if (const auto resolved = store.resolved_model(); resolved && resolved->is_object() && !resolved->contains("analytic"))
    return cases::parse_case(*resolved, std::filesystem::absolute(db).parent_path());
  const auto& model = study.at("model");
  return cases::resolve_case(model.at("case").get<std::string>(), model.value("overrides", nlohmann::json::object()),
                             std::filesystem::absolute(db).parent_path());
}

// The cases of a study's experiments, by experiment name in the study's order: the resolved
// cases its store recorded, else each experiment's case reference resolved beside the store.
std::vector<std::pair<std::string, cases::CaseSpec>> experiment_cases(const identify::StudyStore& store,
                                                                      const nlohmann::json& study,
                                                                      const std::filesystem::path& db) {
  const auto resolved = store.resolved_model();
  const std::filesystem::path folder = std::filesystem::absolute(db).parent_path();
  std::vector<std::pair<std::string, cases::CaseSpec>> out;
  for (const auto& e : study.at("experiments")) {
    const std::string name = e.at("name").get<std::string>();
    if (resolved && resolved->is_object() && resolved->contains(name) && !resolved->at(name).contains("analytic")) {
      out.emplace_back(name, cases::parse_case(resolved->at(name), folder));
      continue;
    }
    const auto& model = e.at("model");
    out.emplace_back(name, cases::resolve_case(model.at("case").get<std::string>(),
                                               model.value("overrides", nlohmann::json::object()), folder));
  }
  return out;
}

void run_export(const std::string& db, const std::string& out_file, const ExportFormat& format, bool force) {
  identify::check_user_text(format.option, out_file);
  if (out_file.empty())
    throw std::runtime_error(std::string(format.option) + ": empty file name; give " + format.example +
                             ", or - for standard output");
  // Refused before the store is read: an existing file without --force, a device, a link, a folder.
  std::error_code error;
  if (std::filesystem::weakly_canonical(std::filesystem::absolute(out_file), error) ==
      std::filesystem::weakly_canonical(std::filesystem::absolute(db), error))
    throw std::runtime_error(std::string(format.option) + ": " + identify::quote_path(out_file) +
                             " is the study store itself; give " + format.example + " name");
  if (out_file != "-") identify::check_user_file(out_file, force, format.option);
  const auto store = identify::StudyStore::open_existing(db);
  const nlohmann::json study = store.study_json();
  const std::string model = study.value("model", nlohmann::json::object()).value("case", std::string());
  if (model == "analytic")
    throw std::runtime_error("export: study store '" + db +
                             "' identifies the \"analytic\" test model, not a DEM case; "
                             "DEM contact export needs a pellet_compression or rotary_drum study");
  if (study.value("model", nlohmann::json::object()).contains("external"))
    throw std::runtime_error("export: study store '" + db +
                             "' identifies an external program's model; its answer is in best_parameters.json "
                             "for that program's own input (export writes demfit's DEM cases only)");
  // Runs of a study with experiments store only the variables (each experiment has its own case
  // values): there is no single full parameter set to write as LS-DYNA cards. The LIGGGHTS
  // snippet is written when every experiment's case gives the same material (liggghts_export.hpp).
  if (study.contains("experiments") && &format == &kLsdynaFormat)
    throw std::runtime_error("export: study store '" + db +
                             "' is a study with several experiments; export needs a "
                             "single-model study (one case, one full parameter set)");
  const auto runs = store.evaluations();
  // The study's answer, the same run as report.md and best_parameters.json (study_answer.hpp).
  const identify::StudyAnswer answer = identify::study_answer(runs, store.result(), db);
  const identify::EvaluationRecord* best = answer.run;
  if (!best) throw std::runtime_error("study store '" + db + "' has no successful run to export");
  char objective[32];
  std::snprintf(objective, sizeof objective, "%.6g", best->objective);
  const std::string title = "study '" + study.value("name", std::string("study")) + "', run " +
                            std::to_string(best->iteration) + "/" + std::to_string(best->point) + ", objective " +
                            objective;
  // The effects without an LS-DYNA field, with their off values: the parameter table.
  const std::string text =
      &format == &kLsdynaFormat
          ? identify::lsdyna_keywords(best->parameters, cases::parameter_descriptors(), title,
                                      export_comments(store, study, db))
          : study.contains("experiments")
              ? cases::liggghts_snippet(experiment_cases(store, study, db), best->parameters,
                                        identified_variables(store, study, best->parameters), title)
              : cases::liggghts_snippet(study_case(store, study, db), best->parameters,
                                        identified_variables(store, study, best->parameters), title);
  if (!answer.finished) std::fprintf(stderr, "demfit: warning: export: %s\n", answer.why.c_str());
  if (out_file == "-") {  // standard output
    std::fwrite(text.data(), 1, text.size(), stdout);
    if (std::fflush(stdout) != 0)
      throw std::runtime_error(std::string(format.option) + " -: writing to standard output failed");
    return;
  }
  identify::write_user_file(out_file, text, force, format.option);
  std::printf("wrote %s\n", identify::printable(out_file).c_str());
}


}  // namespace

void register_export(CLI::App& app) {
  auto export_db = std::make_shared<std::string>();
  auto export_k = std::make_shared<std::string>();
  auto export_liggghts = std::make_shared<std::string>();
  auto export_force = std::make_shared<bool>(false);
  auto* exporter = app.add_subcommand(
      "export",
      "Write the answer's DEM parameters for another DEM code: LS-DYNA cards (--lsdyna: *CONTROL_DISCRETE_ELEMENT, "
      "*DEFINE_DE_TO_SURFACE_COUPLING; fixed 10-character fields) or LIGGGHTS 3.8 input lines (--liggghts: "
      "fix property/global material fixes and the pair_style gran / wall/gran models of a hertz_mindlin case); "
      "identified values with their 95 % intervals as comments, others at the case values, SI units");
  exporter->add_option("store", *export_db, "Study store (study.db)")->required()->check(CLI::ExistingFile);
  auto* lsdyna = exporter->add_option(
      "--lsdyna", *export_k, "Keyword file to write (e.g. out.k), a new regular file; - writes to standard output");
  auto* liggghts = exporter->add_option(
      "--liggghts", *export_liggghts,
      "LIGGGHTS input file to write (e.g. material.in, for the `include` command), a new regular file; - writes to "
      "standard output. Needs a hertz_mindlin case: the lsdyna_linear springs have no LIGGGHTS equivalent");
  lsdyna->excludes(liggghts);
  exporter->add_flag("--force", *export_force, "Replace an existing output file (only a regular file is replaced)");
  exporter->callback([export_db, export_k, export_liggghts, export_force, lsdyna, liggghts] {
    if (lsdyna->count() == 0 && liggghts->count() == 0)
      throw std::runtime_error("export: give --lsdyna FILE (LS-DYNA cards) or --liggghts FILE (LIGGGHTS input)");
    if (lsdyna->count() > 0)
      run_export(*export_db, *export_k, kLsdynaFormat, *export_force);
    else
      run_export(*export_db, *export_liggghts, kLiggghtsFormat, *export_force);
  });
}

}  // namespace demfit::apps
