#pragma once
// Units named in curve column labels (docs/spec.md 4: "volume_cm3", "pressure_MPa"): the text after the
// last '_' is the unit. A measured curve in other units of the same dimension is converted to the
// model's units; a different dimension is refused (a mm3/kPa curve against a cm3/MPa
// model once "identified" the corners of the bounds).
//
// Known units (factor to SI):
//   length  m cm mm um in          area    m2 cm2 mm2
//   volume  m3 cm3 mm3 l L ml mL    pressure Pa kPa MPa GPa bar psi
//   force   N mN kN                torque  Nm mNm Nmm kNm
//   time    s ms us min h          angle   rad deg
// Unit names are case-sensitive (MPa is not mPa). Labels without a known unit are left as they are.
#include <string>

#include "demfit/identify/model.hpp"

namespace demfit::identify {

struct ColumnUnit {
  bool known = false;
  std::string unit;       // e.g. "mm3"
  std::string dimension;  // e.g. "volume"
  double to_si = 1.0;     // value [unit] * to_si = value [SI]
};

ColumnUnit column_unit(const std::string& label);

// Multiplier taking values labelled `from` to values labelled `to`: 1 when either unit is unknown;
// throws std::runtime_error "<field>: ..." when both are known and of different dimensions.
double unit_factor(const std::string& from, const std::string& to, const std::string& field);

}  // namespace demfit::identify
