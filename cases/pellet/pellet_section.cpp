// The "pellet" section of a case file (docs/spec.md 2.1): every field is one row of kPelletFields, from
// which its accepted keys, reading and JSON text follow (section_fields.hpp).
#include <array>

#include "demfit/cases/section_fields.hpp"
#include "pellet_case.hpp"

namespace demfit::cases::detail {
namespace {

using Field = SectionField<PelletSpec>;

// Units: see PelletSpec (case_spec.hpp) and docs/case_format.md.
const std::array<Field, 11> kPelletFields{{
    {"container_diameter", &PelletSpec::container_diameter, Sign::positive},
    {"container_height", &PelletSpec::container_height, Sign::positive},
    {"particle_count", &PelletSpec::particle_count, Sign::any, -kUnbounded, kUnbounded, 1},
    {"fill_seed", &PelletSpec::fill_seed, Sign::any, -kUnbounded, kUnbounded, 0},
    {"fill_normk", &PelletSpec::fill_normk, Sign::positive},
    {"settle_time", &PelletSpec::settle_time, Sign::positive},
    {"piston_speed", &PelletSpec::piston_speed, Sign::positive},
    {"max_pressure", &PelletSpec::max_pressure, Sign::positive},
    {"max_travel", &PelletSpec::max_travel, Sign::positive},
    {"unload", &PelletSpec::unload},
    {"curve_points", &PelletSpec::curve_points, Sign::any, -kUnbounded, kUnbounded, 2},
}};

}  // namespace

PelletSpec parse_pellet_section(const nlohmann::json& section, PelletSpec pellet) {
  require_known_keys(section, "pellet", section_keys<PelletSpec>(kPelletFields));
  read_section_fields<PelletSpec>(section, "pellet", kPelletFields, pellet);
  return pellet;
}

nlohmann::json pellet_section_json(const PelletSpec& pellet) {
  nlohmann::json out = nlohmann::json::object();
  write_section_fields<PelletSpec>(out, kPelletFields, pellet);
  return out;
}

}  // namespace demfit::cases::detail
