// The "external" object of a study's model, read strictly (external_model.hpp,
// docs/external-model.md): every problem is one line naming the field and the fix.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "demfit/identify/external_model.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/template_text.hpp"
#include "json_reader.hpp"

namespace demfit::identify {
namespace {

using detail::JsonReader;

constexpr std::size_t kMaxCommandWords = 256;
constexpr double kMaxTimeLimit = 1.0e7;  // [s] about 116 days: a typo guard, not a budget

std::vector<std::string> parse_command(JsonReader& in) {
  const auto& value = in.raw("command");
  if (!value.is_array() || value.empty() || value.size() > kMaxCommandWords)
    in.fail("command", "expected a non-empty array of strings, the program then its arguments, e.g. "
                       "[\"liggghts\", \"-in\", \"in.sim\"] (no shell: one string per argument)");
  std::vector<std::string> out;
  for (const auto& word : value) {
    if (!word.is_string()) in.fail("command", "expected only strings, got " + json_excerpt(word));
    out.push_back(word.get<std::string>());
    check_user_text(in.field("command") + "[" + std::to_string(out.size() - 1) + "]", out.back());
  }
  if (out[0].empty()) in.fail("command", "the program (first entry) must not be empty");
  return out;
}

// A path the program writes inside its run folder: relative, without "..", never empty.
void check_relative_inside(JsonReader& in, const std::string& key, const std::string& path) {
  check_user_text(in.field(key), path);
  const std::filesystem::path p(path);
  if (path.empty() || p.is_absolute())
    in.fail(key, "'" + path + "' must be a path relative to the run folder, e.g. \"torque.csv\"");
  for (const auto& part : p)
    if (part == "..")
      in.fail(key, "'" + path + "' contains \"..\"; outputs are read only from inside the run folder");
}

ExternalOutput parse_output(const nlohmann::json& json, const std::string& path, const std::string& curve) {
  JsonReader in(json, path);
  ExternalOutput out{curve, in.text("file"), in.text("x"), in.text("y")};
  in.finish();
  check_relative_inside(in, "file", out.file);
  if (out.x_column.empty()) in.fail("x", "must name the CSV column of the abscissa, with its unit (e.g. \"time_s\")");
  if (out.y_column.empty()) in.fail("y", "must name the CSV column of the ordinate, with its unit (e.g. \"torque_Nm\")");
  check_user_text(in.field("x"), out.x_column);
  check_user_text(in.field("y"), out.y_column);
  return out;
}

std::vector<ExternalOutput> parse_outputs(JsonReader& in) {
  const auto& value = in.raw("outputs");
  if (!value.is_object() || value.empty())
    in.fail("outputs", "expected an object of curves, e.g. {\"torque\": {\"file\": \"torque.csv\", \"x\": \"time_s\", "
                       "\"y\": \"torque_Nm\"}}");
  std::vector<ExternalOutput> out;
  for (const auto& item : value.items()) {
    const std::string& curve = item.key();
    check_user_text(in.field("outputs"), curve);
    if (curve.empty() || curve.find_first_of("/@") != std::string::npos)
      in.fail("outputs", "curve name '" + curve + "' must be non-empty and without '/' or '@'");
    out.push_back(parse_output(item.value(), in.field("outputs") + "." + curve, curve));
  }
  return out;
}

std::map<std::string, std::string> parse_units(JsonReader& in) {
  const auto& value = in.raw("parameters");
  if (!value.is_object() || value.empty())
    in.fail("parameters", "expected an object of the template's parameters and their units, e.g. "
                          "{\"sliding_friction\": \"-\", \"youngs_modulus\": \"Pa\"} (\"-\" = dimensionless)");
  std::map<std::string, std::string> out;
  for (const auto& item : value.items()) {
    if (!is_parameter_identifier(item.key()))
      in.fail("parameters", "'" + printable(item.key()) +
                                "' is not a parameter name; use letters, digits and '_' (not starting with a digit, "
                                "at most 64 characters)");
    if (!item.value().is_string() || item.value().get<std::string>().empty())
      in.fail("parameters." + item.key(), "expected the unit as a non-empty string (\"-\" = dimensionless)");
    out[item.key()] = item.value().get<std::string>();
    check_user_text(in.field("parameters." + item.key()), out[item.key()]);
  }
  return out;
}

// "in.sim.template" -> "in.sim": the input name when the study does not give one.
std::string default_input_name(const std::string& template_file) {
  const std::string name = std::filesystem::path(template_file).filename().string();
  const std::string suffix = ".template";
  if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
    return name.substr(0, name.size() - suffix.size());
  return {};
}

// "files": paths relative to the study file; each is copied into the run folder under its file
// name, so two entries may not share one, nor take the input's or an output's name.
std::vector<std::string> parse_files(JsonReader& in) {
  std::vector<std::string> out;
  if (!in.has("files")) return out;
  const auto& value = in.raw("files");
  if (!value.is_array() || value.size() > kMaxCommandWords)
    in.fail("files", "expected an array of file paths relative to the study file, e.g. [\"drum.stl\"]");
  std::set<std::string> names;
  for (const auto& item : value) {
    if (!item.is_string()) in.fail("files", "expected only strings, got " + json_excerpt(item));
    out.push_back(item.get<std::string>());
    check_user_text(in.field("files"), out.back());
    const std::string name = std::filesystem::path(out.back()).filename().string();
    if (name.empty() || name == "." || name == "..")
      in.fail("files", "'" + out.back() + "' does not name a file");
    if (!names.insert(name).second)
      in.fail("files", "two files are named '" + name + "' in the run folder; rename one");
  }
  return out;
}

// One "candidates" entry: {"name", "parameter", "off", "range": [lower, upper], optional "unit"
// (must be the parameter's declared one), "description", "curves" (output names)}.
ExternalCandidate parse_candidate(const nlohmann::json& json, const std::string& path, const ExternalModelSpec& spec) {
  JsonReader in(json, path);
  ExternalCandidate c;
  c.name = in.text("name");
  if (!is_parameter_identifier(c.name))
    in.fail("name", "'" + printable(c.name) + "' is not an effect name; use letters, digits and '_' (e.g. \"cohesion\")");
  c.parameter = in.text("parameter");
  const auto declared = spec.units.find(c.parameter);
  if (declared == spec.units.end())
    in.fail("parameter", "'" + printable(c.parameter) +
                             "' is not a parameter of the template; name one declared in model.external.parameters "
                             "and used as {{name}} in the template");
  c.off_value = in.number("off");
  const auto& range = in.raw("range");
  if (!range.is_array() || range.size() != 2 || !range[0].is_number() || !range[1].is_number())
    in.fail("range", "expected [lower, upper] in the parameter's unit, e.g. [0, 1e5]");
  c.lower = range[0].get<double>();
  c.upper = range[1].get<double>();
  if (!(std::isfinite(c.lower) && std::isfinite(c.upper) && c.lower < c.upper))
    in.fail("range", "lower must be below upper, both finite");
  if (!std::isfinite(c.off_value) || c.off_value < c.lower || c.off_value > c.upper)
    in.fail("off", "the off value " + json_excerpt(in.raw("off")) + " lies outside the range [" +
                       json_excerpt(range[0]) + ", " + json_excerpt(range[1]) +
                       "]; give the value at which the effect vanishes, inside the range");
  if (in.has("unit") && in.text("unit") != declared->second)
    in.fail("unit", "'" + printable(in.text("unit")) + "' differs from the unit of parameter '" + c.parameter +
                        "' in model.external.parameters ('" + declared->second + "'); give that unit or omit it");
  c.description = in.text_or("description", c.parameter + " from " + json_excerpt(in.raw("off")) + " (off)");
  check_user_text(in.field("description"), c.description);
  if (in.has("curves")) {
    const auto& curves = in.raw("curves");
    if (!curves.is_array()) in.fail("curves", "expected an array of output curve names, e.g. [\"torque\"]");
    for (const auto& curve : curves) {
      const bool known = curve.is_string() && std::any_of(spec.outputs.begin(), spec.outputs.end(), [&](const auto& o) {
                           return o.curve == curve.get<std::string>();
                         });
      if (!known) in.fail("curves", json_excerpt(curve) + " is not a curve of model.external.outputs");
      c.curves.push_back(curve.get<std::string>());
    }
  }
  in.finish();
  return c;
}

std::vector<ExternalCandidate> parse_candidates(JsonReader& in, const ExternalModelSpec& spec) {
  std::vector<ExternalCandidate> out;
  if (!in.has("candidates")) return out;
  const auto& value = in.raw("candidates");
  if (!value.is_array() || value.size() > kMaxCommandWords)
    in.fail("candidates", "expected an array of effects, e.g. [{\"name\": \"cohesion\", \"parameter\": \"ced\", "
                          "\"off\": 0, \"range\": [0, 1e5]}]");
  std::set<std::string> names, parameters;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string path = in.field("candidates") + "[" + std::to_string(i) + "]";
    out.push_back(parse_candidate(value[i], path, spec));
    const JsonReader item(value[i], path);
    if (!names.insert(out.back().name).second)
      item.fail("name", "'" + out.back().name + "' names two candidates; give each its own name");
    if (!parameters.insert(out.back().parameter).second)
      item.fail("parameter", "'" + out.back().parameter +
                                 "' is the parameter of an earlier candidate; one candidate per parameter");
  }
  return out;
}

}  // namespace

ExternalModelSpec parse_external_spec(const nlohmann::json& json, const std::string& field) {
  JsonReader in(json, field);
  ExternalModelSpec spec;
  spec.command = parse_command(in);
  spec.template_file = in.text("template");
  check_user_text(in.field("template"), spec.template_file);
  if (spec.template_file.empty()) in.fail("template", "must name the input template file (relative to the study file)");
  spec.input_file = in.text_or("input", default_input_name(spec.template_file));
  if (spec.input_file.empty())
    in.fail("input", "give the file name the program reads in its run folder, e.g. \"in.sim\"");
  check_user_text(in.field("input"), spec.input_file);
  if (spec.input_file == "." || spec.input_file == ".." || spec.input_file.find('/') != std::string::npos)
    in.fail("input", "'" + spec.input_file + "' must be a plain file name (written into each run folder)");
  spec.units = parse_units(in);
  spec.time_limit_s = in.number("time_limit_s");
  if (!(spec.time_limit_s > 0.0 && spec.time_limit_s <= kMaxTimeLimit))
    in.fail("time_limit_s", "must be > 0 and at most 1e7 seconds (the wall time after which a run is killed)");
  spec.outputs = parse_outputs(in);
  spec.files = parse_files(in);
  spec.candidates = parse_candidates(in, spec);
  in.finish();
  for (const auto& f : spec.files) {
    const std::string name = std::filesystem::path(f).filename().string();
    if (name == spec.input_file || name == "stdout.txt" || name == "stderr.txt" || name == "demfit_run.json")
      in.fail("files", "'" + f + "' would take the name of a file demfit writes (" + name + "); rename it");
    for (const auto& o : spec.outputs)
      if (o.file == name) in.fail("files", "'" + f + "' has the name of output '" + o.curve + "'; rename it");
  }
  for (const auto& o : spec.outputs)
    if (o.file == spec.input_file || o.file == "stdout.txt" || o.file == "stderr.txt" || o.file == "demfit_run.json")
      in.fail("outputs." + o.curve + ".file", "'" + o.file + "' is a file demfit writes; name the program's own CSV");
  return spec;
}

nlohmann::json to_json(const ExternalModelSpec& spec) {
  nlohmann::json outputs = nlohmann::json::object();
  for (const auto& o : spec.outputs) outputs[o.curve] = {{"file", o.file}, {"x", o.x_column}, {"y", o.y_column}};
  nlohmann::json json = {{"command", spec.command},  {"template", spec.template_file},   {"input", spec.input_file},
                         {"parameters", spec.units}, {"time_limit_s", spec.time_limit_s}, {"outputs", outputs}};
  if (!spec.files.empty()) json["files"] = spec.files;  // written only when given
  if (!spec.candidates.empty()) {  // written only when given: a study without them keeps its fingerprint
    nlohmann::json candidates = nlohmann::json::array();
    for (const auto& c : spec.candidates) {
      nlohmann::json one = {{"name", c.name},
                            {"parameter", c.parameter},
                            {"off", c.off_value},
                            {"range", {c.lower, c.upper}},
                            {"description", c.description}};
      if (!c.curves.empty()) one["curves"] = c.curves;
      candidates.push_back(one);
    }
    json["candidates"] = candidates;
  }
  return json;
}

}  // namespace demfit::identify
