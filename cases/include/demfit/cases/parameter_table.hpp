#pragma once
// The model parameters of the DEM cases, one row each: name, unit, meaning,
// valid range, default, the off value of an effect, where the parameter lives, its LS-DYNA card
// and field, the contact laws it belongs to, its case-file field and how to read and write it on
// a CaseSpec. Everything else is derived from this table: case-file ranges of these fields,
// parameter_names(), with_parameters / parameters_of, `demfit simulate --set` help, the effect
// catalogue's parameters, the descriptors identify checks study bounds against, the LS-DYNA
// export's effect warnings and docs/parameters.md (`demfit parameters`).
// Adding a parameter: one row in parameter_table.cpp plus its physics (docs/parameters.md).
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/parameter_descriptor.hpp"

namespace demfit::cases {

// Where a parameter lives: a particle-pair contact value, a particle-wall value, an effect of
// the effects library (off at its off value), or the case's fill.
enum class ParameterHome { pair_contact, wall_contact, effect, fill };

// The contact laws a parameter belongs to: one bit per dem_core::ContactLawKind (law_bit), so a
// third law is one more bit, never a silent "the other one".
constexpr unsigned law_bit(dem_core::ContactLawKind law) { return 1u << static_cast<unsigned>(law); }
enum class ParameterLaws : unsigned {
  lsdyna_linear = law_bit(dem_core::ContactLawKind::lsdyna_linear),
  hertz_mindlin = law_bit(dem_core::ContactLawKind::hertz_mindlin),
  both = lsdyna_linear | hertz_mindlin,
};

struct ParameterRow {
  const char* name;                // identified-parameter name (study variables, --set, fixed overrides)
  const char* unit;                // "-" for dimensionless
  const char* meaning;             // one line
  identify::ParameterRange valid;  // accepted by the case file, --set, studies and dem_core
  double default_value;            // NaN when the case gives it (no default)
  bool is_effect;                  // switches an effect of the catalogue on; off_value meaningful
  double off_value;                // value at which the effect is absent (effects only)
  ParameterHome home;
  const char* lsdyna;  // "*CARD FIELD"; "" when LS-DYNA has no such field
  ParameterLaws laws;
  bool drum_only;          // exists in rotary_drum cases only
  const char* case_path;   // dotted case-file field of lsdyna_linear files ("contact.normk")
  const char* hertz_path;  // the field in hertz_mindlin files when it differs, else nullptr
  double (*get)(const CaseSpec&);
  void (*set)(CaseSpec&, double);  // value already checked against `valid`

  [[nodiscard]] bool applies_to(dem_core::ContactLawKind law) const;
};

// All rows, in the fixed order of parameter_names().
const std::vector<ParameterRow>& parameter_table();

// The row named `name`, or nullptr.
const ParameterRow* find_parameter(std::string_view name);

// The row whose case-file field is `path` ("contact.ndamp", "wall_contact.fricr" of a Hertz
// file), or nullptr.
const ParameterRow* find_parameter_by_path(std::string_view path);

// "normk sheark ... fill_volume_ml": the names, space-separated (error messages).
std::string parameter_names_text();

// The names of the laws in `laws`, comma-separated (law registry order).
std::string laws_text(ParameterLaws laws);

// identify's view of a row / of all rows.
identify::ParameterDescriptor descriptor_of(const ParameterRow& row);
std::vector<identify::ParameterDescriptor> parameter_descriptors();

// Throws "parameter 'name' = value must lie in <range> [unit]" when `value` is outside the row's
// valid range.
void check_parameter_value(const ParameterRow& row, double value);

// Reads the case-file field `path`.`key` (a table row's case_path or hertz_path) with the row's
// valid range; `fallback` when absent. Errors name the dotted field. Throws std::logic_error when
// the field is not a table row (a programming error).
double read_parameter(const nlohmann::json& object, std::string_view path, const char* key, double fallback);

// Case-file fields of the rows under `section` ("contact", "wall_contact") of a `law` case file:
// their keys (Hertz files use a row's hertz_path), reading them into `spec` (absent keys keep
// spec's value; ranges from the rows) and writing them from `spec`.
std::vector<std::string> parameter_keys(std::string_view section, dem_core::ContactLawKind law);
void read_parameter_fields(const nlohmann::json& object, std::string_view section, dem_core::ContactLawKind law,
                           CaseSpec& spec);
void write_parameter_fields(nlohmann::json& object, std::string_view section, dem_core::ContactLawKind law,
                            const CaseSpec& spec);

// Reads `contact.<key>` as one of the named `models` (dem_core::kCohesionModels,
// kRollingModels); `fallback` when absent; an unknown name is an error naming the field and the
// accepted names.
template <class Model, std::size_t N>
Model read_contact_model(const nlohmann::json& contact, const char* key,
                         const std::pair<Model, const char*> (&models)[N], Model fallback);

// One line per row for `demfit simulate --set` help: "name [unit] range: meaning".
std::string parameter_help_text();

// The table as Markdown (docs/parameters.md is this text; `demfit parameters` prints it).
std::string parameters_markdown();

}  // namespace demfit::cases
