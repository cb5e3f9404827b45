// `demfit reproduce table2`: Table 2 with numbers for the drum's original powder.
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/reproduce.hpp"
#include "demfit/cases/reproduce_tables.hpp"
#include "builtin_cases.hpp"

namespace demfit::cases {

std::string reproduce_table2(const ReproduceOptions&) {
  const CaseSpec drum = parse_case(nlohmann::json::parse(detail::kBuiltinRotaryDrum));
  return format_table2({drum.material.radius, drum.material.density}, drum.drum.volume_fraction, {1.0, 2.0, 4.0});
}

}  // namespace demfit::cases
