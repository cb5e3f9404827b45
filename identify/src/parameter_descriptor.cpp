// Parameter descriptors (see parameter_descriptor.hpp).
#include "demfit/identify/parameter_descriptor.hpp"

#include <cmath>
#include <cstdio>

namespace demfit::identify {
namespace {

std::string number(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

bool ParameterRange::contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool above = lower_open ? value > lower : value >= lower;
  const bool below = upper_open ? value < upper : value <= upper;
  return above && below;
}

bool ParameterRange::contains_interval(double lo, double hi) const { return lo <= hi && contains(lo) && contains(hi); }

std::string ParameterRange::to_string() const {
  const bool open_lo = lower_open || std::isinf(lower);
  const bool open_hi = upper_open || std::isinf(upper);
  std::string text(1, open_lo ? '(' : '[');  // appended: GCC 12 warns (-Wrestrict) on "literal" + string
  text += number(lower);
  text += ", ";
  text += number(upper);
  text += open_hi ? ')' : ']';
  return text;
}

const ParameterDescriptor* find_descriptor(const std::vector<ParameterDescriptor>& descriptors,
                                           const std::string& name) {
  for (const auto& d : descriptors)
    if (d.name == name) return &d;
  return nullptr;
}

std::vector<ParameterDescriptor> unbounded_descriptors(const std::vector<std::string>& names) {
  std::vector<ParameterDescriptor> out;
  for (const auto& n : names) {
    ParameterDescriptor d;
    d.name = n;
    out.push_back(d);
  }
  return out;
}

}  // namespace demfit::identify
