// Studies from Python: demfit.identify / demfit.resume run the identification loop as
// `demfit identify STUDY.json --out DIR [--resume]` does (same checks, same store, same files),
// and demfit.open_study reads a store: its answer (identify/study_answer.hpp, the one rule every
// output uses), the reported 95 % intervals (reported_interval.hpp, as best_parameters.json) and
// every run's parameters and objective.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "demfit/cases/study_model.hpp"
#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/store_lock.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_answer.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/study_store.hpp"
#include "demfit/identify/study_warnings.hpp"

namespace demfit::python {

namespace {

namespace fs = std::filesystem;

// A study store read once: the store is closed again, so the object holds no file.
struct Study {
  fs::path path;
  nlohmann::json study;
  std::vector<identify::EvaluationRecord> runs;
  std::optional<nlohmann::json> result;
  std::vector<std::string> warnings;

  const identify::EvaluationRecord* answer_run(identify::StudyAnswer* answer = nullptr) const {
    const identify::StudyAnswer a = identify::study_answer(runs, result, path.string());
    if (answer) *answer = a;
    return a.run;
  }
};

// A study.db file, or a folder holding one.
Study open_study(const fs::path& location) {
  std::error_code error;
  const fs::path db = fs::is_directory(location, error) ? location / "study.db" : location;
  const identify::StudyStore store = identify::StudyStore::open_existing(db);
  return Study{db, store.study_json(), store.evaluations(), store.result(),
               identify::study_diagnostics(store).warnings};
}

py::object answer(const Study& s) {
  identify::StudyAnswer a;
  const identify::EvaluationRecord* run = s.answer_run(&a);
  if (!run) return py::none();
  py::dict out;
  out["parameters"] = to_python(run->parameters);
  out["objective"] = run->objective;
  out["run"] = py::make_tuple(run->iteration, run->point);
  out["finished"] = a.finished;
  out["converged"] = s.result ? s.result->value("converged", false) : false;
  out["why"] = a.why;
  out["curves"] = to_python(run->curves);
  return out;
}

// As best_parameters.json: reported_interval of the stored uncertainty at the answer's value.
py::dict intervals(const Study& s) {
  py::dict out;
  const identify::EvaluationRecord* run = s.answer_run();
  if (!run) return out;
  const nlohmann::json uncertainty = s.result ? s.result->value("uncertainty", nlohmann::json()) : nlohmann::json();
  for (const auto& v : s.study.value("variables", nlohmann::json::array())) {
    const std::string name = v.value("name", std::string());
    const auto value = run->parameters.find(name);
    if (value == run->parameters.end()) continue;
    py::dict entry;
    entry["value"] = value->second;
    entry["available"] = false;
    if (uncertainty.is_object()) {
      const identify::ReportedInterval i = identify::reported_interval(uncertainty, name, value->second);
      entry["available"] = i.available;
      entry["lower"] = i.lower;
      entry["upper"] = i.upper;
      entry["identifiable"] = i.identifiable;
      entry["method"] = i.method;
    }
    out[py::str(name)] = entry;
  }
  return out;
}

py::list runs(const Study& s) {
  py::list out;
  for (const auto& r : s.runs) {
    py::dict run;
    run["iteration"] = r.iteration;
    run["point"] = r.point;
    run["kind"] = r.kind;
    run["parameters"] = to_python(r.parameters);
    run["objective"] = r.objective;
    run["ok"] = r.ok;
    run["error"] = r.error;
    run["wall_seconds"] = r.wall_seconds;
    out.append(run);
  }
  return out;
}

Study run_identify(const fs::path& study_file, const std::optional<fs::path>& out, int jobs,
                   int threads_per_job, bool resume, bool plots, bool progress) {
  if (jobs < 1) input_error("jobs: must be >= 1");
  if (threads_per_job < 1) input_error("threads_per_job: must be >= 1");
  identify::RunOptions options;
  options.jobs = jobs;
  options.threads_per_job = threads_per_job;
  options.resume = resume;
  options.plots = plots;
  options.progress = progress;
  options.output_dir = out ? *out : fs::path(study_file.stem().string() + "_results");
  {
    py::gil_scoped_release release;
    // Every configuration error before anything is created: the study, the output folder rules,
    // the model, then one evaluation at the initial point (curve names, units, overlap).
    cases::run_study_file(identify::load_study_file(study_file), study_file, options, "resume=True", "out");
  }
  return open_study(options.output_dir / "study.db");
}

}  // namespace

void register_study(py::module_& m) {
  py::class_<Study>(m, "Study", "A study store read once (study.db); the file is not kept open.")
      .def_property_readonly("path", [](const Study& s) { return s.path.string(); })
      .def_property_readonly("name", [](const Study& s) { return s.study.value("name", std::string()); })
      .def_property_readonly(
          "variables",
          [](const Study& s) {
            std::vector<std::string> names;
            for (const auto& v : s.study.value("variables", nlohmann::json::array()))
              names.push_back(v.value("name", std::string()));
            return names;
          },
          "names of the identified variables, in study order")
      .def_property_readonly("finished", [](const Study& s) { return s.result.has_value(); })
      .def_property_readonly(
          "answer", &answer,
          "the study's answer (the run best_parameters.json and report.md name): dict with parameters, objective, "
          "run (iteration, point), finished, converged, why (the rule that chose it) and curves; None when no run "
          "succeeded. An unfinished study offers its lowest run so far (finished False).")
      .def_property_readonly("intervals", &intervals,
                             "variable -> dict value, available, lower, upper (95 %, model units), identifiable, "
                             "method: the interval of best_parameters.json and report.md")
      .def_property_readonly("runs", &runs,
                             "every run in (iteration, point) order: dict iteration, point, kind, parameters, "
                             "objective (NaN when failed), ok, error, wall_seconds")
      .def_property_readonly(
          "study", [](const Study& s) { return to_python(s.study); }, "the resolved study, as study_resolved.json")
      .def_readonly("warnings", &Study::warnings, "the report's warnings, one sentence each")
      .def("__repr__", [](const Study& s) {
        return "<demfit.Study '" + s.study.value("name", std::string()) + "' " + s.path.string() + ", " +
               std::to_string(s.runs.size()) + " runs" + (s.result ? ", finished>" : ", not finished>");
      });
  m.def("open_study", &open_study, py::arg("store"),
        "Read a study store: a study.db file or the folder holding it. Raises demfit.Error naming the store when "
        "it is missing, damaged or of another schema.");
  const char* identify_doc =
      "Run a study file as `demfit identify STUDY --out OUT` and return its demfit.Study.\n\n"
      "out: output folder (default <study stem>_results); the same folder rules, store and result files as the "
      "command line. jobs: simulations at once; threads_per_job: OpenMP threads each (results do not depend on "
      "them). resume: continue the store in out without repeating finished runs. plots: call gnuplot. progress: "
      "progress lines on stderr. The GIL is released during the runs.";
  m.def("identify", &run_identify, py::arg("study"), py::arg("out") = py::none(), py::arg("jobs") = 1,
        py::arg("threads_per_job") = 1, py::arg("resume") = false, py::arg("plots") = false,
        py::arg("progress") = false, identify_doc);
  m.def(
      "resume",
      [](const fs::path& study_file, const std::optional<fs::path>& out, int jobs, int threads_per_job,
         bool plots, bool progress) {
        return run_identify(study_file, out, jobs, threads_per_job, true, plots, progress);
      },
      py::arg("study"), py::arg("out") = py::none(), py::arg("jobs") = 1, py::arg("threads_per_job") = 1,
      py::arg("plots") = false, py::arg("progress") = false,
      "identify(..., resume=True): continue the study stored in out; a finished study reruns nothing.");
}

}  // namespace demfit::python
