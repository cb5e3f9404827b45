#include "demfit/identify/units.hpp"

#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace demfit::identify {
namespace {

const std::map<std::string, std::pair<const char*, double>>& unit_table() {
  static const std::map<std::string, std::pair<const char*, double>> table = {
      {"m", {"length", 1.0}},
      {"cm", {"length", 1e-2}},
      {"mm", {"length", 1e-3}},
      {"um", {"length", 1e-6}},
      {"in", {"length", 0.0254}},
      {"m2", {"area", 1.0}},
      {"cm2", {"area", 1e-4}},
      {"mm2", {"area", 1e-6}},
      {"m3", {"volume", 1.0}},
      {"cm3", {"volume", 1e-6}},
      {"mm3", {"volume", 1e-9}},
      {"l", {"volume", 1e-3}},
      {"L", {"volume", 1e-3}},
      {"ml", {"volume", 1e-6}},
      {"mL", {"volume", 1e-6}},
      {"Pa", {"pressure", 1.0}},
      {"kPa", {"pressure", 1e3}},
      {"MPa", {"pressure", 1e6}},
      {"GPa", {"pressure", 1e9}},
      {"bar", {"pressure", 1e5}},
      {"psi", {"pressure", 6894.757293168}},
      {"N", {"force", 1.0}},
      {"mN", {"force", 1e-3}},
      {"kN", {"force", 1e3}},
      {"Nm", {"torque", 1.0}},
      {"mNm", {"torque", 1e-3}},
      {"Nmm", {"torque", 1e-3}},
      {"kNm", {"torque", 1e3}},
      {"s", {"time", 1.0}},
      {"ms", {"time", 1e-3}},
      {"us", {"time", 1e-6}},
      {"min", {"time", 60.0}},
      {"h", {"time", 3600.0}},
      {"rad", {"angle", 1.0}},
      {"deg", {"angle", std::numbers::pi / 180.0}}};
  return table;
}

}  // namespace

ColumnUnit column_unit(const std::string& label) {
  ColumnUnit out;
  const auto underscore = label.rfind('_');
  if (underscore == std::string::npos) return out;
  out.unit = label.substr(underscore + 1);
  const auto found = unit_table().find(out.unit);
  if (found == unit_table().end()) return out;
  out.known = true;
  out.dimension = found->second.first;
  out.to_si = found->second.second;
  return out;
}

double unit_factor(const std::string& from, const std::string& to, const std::string& field) {
  const ColumnUnit a = column_unit(from), b = column_unit(to);
  if (!a.known || !b.known) return 1.0;
  if (a.dimension != b.dimension)
    throw std::runtime_error(field + ": '" + from + "' is a " + a.dimension + " [" + a.unit +
                             "] but the model's column '" + to + "' is a " + b.dimension + " [" + b.unit +
                             "]; give a column of the same quantity");
  return a.to_si / b.to_si;
}

}  // namespace demfit::identify
