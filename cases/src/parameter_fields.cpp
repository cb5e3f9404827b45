// The case-file fields of the parameter table: which keys a section holds, reading and writing
// them (see parameter_table.hpp). The case parser and to_json use these, so a new row's field
// is read, range-checked and written back without further edits.
#include <stdexcept>
#include <string>

#include "demfit/cases/json_fields.hpp"
#include "demfit/cases/parameter_table.hpp"

namespace demfit::cases {
namespace {

// The row's field in a `law` case file, split into section and key; empty section when the row
// does not exist under that law.
std::pair<std::string, std::string> field_of(const ParameterRow& row, dem_core::ContactLawKind law) {
  if (!row.applies_to(law)) return {};
  const std::string path =
      law == dem_core::ContactLawKind::hertz_mindlin && row.hertz_path ? row.hertz_path : row.case_path;
  const auto dot = path.find('.');
  return {path.substr(0, dot), path.substr(dot + 1)};
}

}  // namespace

template <class Model, std::size_t N>
Model read_contact_model(const nlohmann::json& contact, const char* key,
                         const std::pair<Model, const char*> (&models)[N], Model fallback) {
  const std::string text = read_string(contact, "contact", key, dem_core::model_name(models, fallback));
  std::string names;
  for (const auto& [m, name] : models) {
    if (text == name) return m;
    names += (names.empty() ? "\"" : " or \"") + std::string(name) + "\"";
  }
  throw std::runtime_error("'contact." + std::string(key) + "' must be " + names + " (got \"" + text + "\")");
}
template dem_core::CohesionModel read_contact_model(const nlohmann::json&, const char*,
                                                    const std::pair<dem_core::CohesionModel, const char*> (&)[2],
                                                    dem_core::CohesionModel);
template dem_core::RollingModel read_contact_model(const nlohmann::json&, const char*,
                                                   const std::pair<dem_core::RollingModel, const char*> (&)[2],
                                                   dem_core::RollingModel);

std::vector<std::string> parameter_keys(std::string_view section, dem_core::ContactLawKind law) {
  std::vector<std::string> keys;
  for (const ParameterRow& row : parameter_table()) {
    const auto [s, key] = field_of(row, law);
    if (s == section) keys.push_back(key);
  }
  return keys;
}

void read_parameter_fields(const nlohmann::json& object, std::string_view section, dem_core::ContactLawKind law,
                           CaseSpec& spec) {
  for (const ParameterRow& row : parameter_table()) {
    const auto [s, key] = field_of(row, law);
    if (s != section || !object.contains(key)) continue;
    row.set(spec, read_parameter(object, section, key.c_str(), row.get(spec)));
  }
}

void write_parameter_fields(nlohmann::json& object, std::string_view section, dem_core::ContactLawKind law,
                            const CaseSpec& spec) {
  for (const ParameterRow& row : parameter_table()) {
    const auto [s, key] = field_of(row, law);
    if (s == section) object[key] = row.get(spec);
  }
}

}  // namespace demfit::cases
