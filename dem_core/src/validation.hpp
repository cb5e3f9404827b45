#pragma once
// Small helpers that throw std::runtime_error with a one-line message naming the field.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

[[noreturn]] inline void fail(const std::string& field, double value, const std::string& rule) {
  std::ostringstream out;
  out.precision(6);
  out << field << " = " << value << ": " << rule;
  throw std::runtime_error(out.str());
}
inline void require_finite(const std::string& field, double value) {
  if (!std::isfinite(value)) fail(field, value, "must be a finite number");
}
inline void require_positive(const std::string& field, double value) {
  require_finite(field, value);
  if (value <= 0.0) fail(field, value, "must be > 0");
}
inline void require_non_negative(const std::string& field, double value) {
  require_finite(field, value);
  if (value < 0.0) fail(field, value, "must be >= 0");
}
/// Damping ratios: [0, 1) (critical damping and above have no restitution formula).
inline void require_fraction(const std::string& field, double value) {
  require_finite(field, value);
  if (value < 0.0 || value >= 1.0) fail(field, value, "must lie in [0, 1)");
}
inline void require_finite(const std::string& field, const Vec3& v) {
  if (!is_finite(v)) {
    std::ostringstream out;
    out << field << " = (" << v.x << ", " << v.y << ", " << v.z << "): must be finite numbers";
    throw std::runtime_error(out.str());
  }
}
/// Returns v/|v|; throws if v is zero or not finite.
inline Vec3 require_direction(const std::string& field, const Vec3& v) {
  require_finite(field, v);
  if (norm2(v) == 0.0) throw std::runtime_error(field + " = (0, 0, 0): must be a non-zero direction");
  return normalized(v);
}

}  // namespace demfit::dem_core
