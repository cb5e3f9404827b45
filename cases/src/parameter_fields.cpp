// The case-file fields of the parameter table: which keys a section holds, reading and writing
// them (see parameter_table.hpp). The case parser and to_json use these, so a new row's field
// is read, range-checked and written back without further edits.
#include <string>

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
