// demfit.simulate: one case run with overrides, its curves as NumPy arrays. The same steps as the
// command line's `demfit simulate CASE --set ...`: identified parameters act on the measured stage
// only (the cached fill is shared), any other dotted field edits the case before it is parsed.
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"

namespace demfit::python {

namespace {

struct SimulationResult {
  identify::CurveSet curves;
  std::map<std::string, cases::CurveTable> tables;
  std::vector<std::pair<std::string, std::string>> summary;
  nlohmann::json resolved_case;
  identify::ParameterSet parameters;
};

// A case file, or a built-in case name ("pellet_compression", "rotary_drum") when no such file
// exists; the folder against which the case's relative file references resolve.
nlohmann::json case_document(const std::string& reference, std::filesystem::path& base_dir) {
  std::error_code error;
  if (std::filesystem::exists(reference, error) || reference.find('/') != std::string::npos ||
      std::filesystem::path(reference).extension() == ".json") {
    base_dir = std::filesystem::path(reference).parent_path();
    return cases::read_case_json(reference);
  }
  base_dir = std::filesystem::current_path();
  return cases::to_json(cases::resolve_case(reference, nlohmann::json::object(), base_dir));
}

// overrides: {name: value}. A parameter-table name takes a finite number; any other name is a
// dotted case field set to the value as JSON (cases::apply_setting, the rule of --set).
void apply_overrides(const py::dict& overrides, nlohmann::json& document, identify::ParameterSet& parameters) {
  for (const auto& [key, value] : overrides) {
    if (!py::isinstance<py::str>(key)) input_error("overrides: keys must be strings (a parameter or a dotted field)");
    const std::string name = key.cast<std::string>();
    if (!cases::parameter_path(name).empty()) {
      if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)))
        input_error("overrides['" + name + "']: give a number (`demfit parameters` lists its unit and range)");
      const double number = value.cast<double>();
      if (!std::isfinite(number))
        input_error("overrides['" + name + "']: " + std::string(py::str(value)) +
                    " is not a finite number; give a value in its range (`demfit parameters`)");
      parameters[name] = number;
    } else {
      cases::apply_setting(document, name + "=" + to_json(value, "overrides['" + name + "']").dump());
    }
  }
}

SimulationResult simulate(const std::filesystem::path& case_reference, const std::optional<py::dict>& overrides,
                          int threads, const std::optional<std::filesystem::path>& cache_dir) {
  if (threads < 1) input_error("threads: must be >= 1 (OpenMP threads of the simulation)");
  std::filesystem::path base_dir;
  nlohmann::json document = case_document(case_reference.string(), base_dir);
  identify::ParameterSet parameters;
  if (overrides) apply_overrides(*overrides, document, parameters);
  const cases::CaseSpec spec = cases::parse_case(document, base_dir);
  cases::CaseRunOptions options;
  options.threads = threads;
  if (cache_dir) options.cache_dir = *cache_dir;
  SimulationResult out;
  {
    py::gil_scoped_release release;
    cases::CaseResult result = cases::run_case(spec, parameters, options);
    out.curves = std::move(result.curves);
    out.tables = std::move(result.tables);
    out.summary = std::move(result.summary);
  }
  out.resolved_case = cases::to_json(spec);
  out.parameters = parameters;
  return out;
}

py::dict tables_to_python(const std::map<std::string, cases::CurveTable>& tables) {
  py::dict out;
  for (const auto& [stem, table] : tables) {
    py::dict columns;
    for (std::size_t c = 0; c < table.columns.size() && c < table.values.size(); ++c)
      columns[py::str(table.columns[c])] = to_array(table.values[c]);
    out[py::str(stem)] = columns;
  }
  return out;
}

}  // namespace

void register_simulate(py::module_& m) {
  py::class_<SimulationResult>(m, "SimulationResult", "The result of demfit.simulate.")
      .def_property_readonly(
          "curves", [](const SimulationResult& r) { return to_python(r.curves); },
          "dict: curve name -> demfit.Curve (the files <curve>.csv of `demfit simulate`)")
      .def_property_readonly(
          "tables", [](const SimulationResult& r) { return tables_to_python(r.tables); },
          "dict: table name (history, ...) -> {column name with unit: NumPy array}")
      .def_readonly("summary", &SimulationResult::summary, "list of (label with unit, value) lines of summary.txt")
      .def_property_readonly(
          "case", [](const SimulationResult& r) { return to_python(r.resolved_case); },
          "the resolved case (every default filled in), as case_resolved.json")
      .def_property_readonly(
          "parameters", [](const SimulationResult& r) { return to_python(r.parameters); },
          "the identified parameters given as overrides (they act on the measured stage only)");
  m.def("simulate", &simulate, py::arg("case"), py::arg("overrides") = py::none(), py::arg("threads") = 1,
        py::arg("cache_dir") = py::none(),
        "Run one case and return its curves.\n\n"
        "case: a case JSON file, or a built-in case name ('pellet_compression', 'rotary_drum').\n"
        "overrides: {name: value} as `demfit simulate --set name=value`: identified parameters (`demfit "
        "parameters`, e.g. 'normk') act on the measured stage; any other dotted case field (e.g. "
        "'pellet.piston_speed': 0.1 [m/s]) edits the case.\n"
        "threads: OpenMP threads. cache_dir: folder of cached fills (default $DEMFIT_CACHE_DIR, else "
        "~/.cache/demfit).\nThe GIL is released while the case runs. Raises demfit.InputError on bad input, "
        "demfit.Error when the run fails.");
}

}  // namespace demfit::python
