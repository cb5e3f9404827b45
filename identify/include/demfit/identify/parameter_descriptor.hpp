#pragma once
// What a model says about one of its parameters: name, unit and the range of
// values it accepts, so a study's bounds are checked against the model before anything runs.
// The DEM cases fill these from their parameter table (cases/parameter_table.hpp); identify
// knows nothing of DEM beyond these fields.
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace demfit::identify {

// An interval of accepted values; each end closed ("[") or open ("("); an infinite end is open.
struct ParameterRange {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_open = false;
  bool upper_open = false;

  [[nodiscard]] bool contains(double value) const;
  // True when every value of the closed interval [lo, hi] lies in this range.
  [[nodiscard]] bool contains_interval(double lo, double hi) const;
  // "[0, 1)", "(0, inf)", "[1, 100]" (values with %g).
  [[nodiscard]] std::string to_string() const;
};

struct ParameterDescriptor {
  std::string name;
  std::string unit;      // "-" for dimensionless; "" when the model does not say
  ParameterRange valid;  // values evaluate() accepts
  double default_value = 0.0;
  std::optional<double> off_value;  // value at which an effect parameter switches its effect off
  std::string lsdyna_field;         // "*CONTROL_DISCRETE_ELEMENT NORMK"; empty when LS-DYNA has none
};

// A parameter an effect adds, with its FITTING range [lower, upper] (inside the parameter's
// valid range, possibly narrower) and the value at which the effect is absent. Used by the case
// effect catalogue and by diagnose's candidates alike.
struct EffectParameter {
  std::string name;    // model parameter name
  double lower = 0.0;  // fitting bounds, model units
  double upper = 1.0;
  double off_value = 0.0;  // value at which the effect vanishes (inside [lower, upper])
  std::string unit;        // "-" for dimensionless
};

// The descriptor named `name` in `descriptors`, or nullptr.
const ParameterDescriptor* find_descriptor(const std::vector<ParameterDescriptor>& descriptors,
                                           const std::string& name);
// Not on a temporary (e.g. model.parameters()): the pointer would dangle (found by AddressSanitizer).
const ParameterDescriptor* find_descriptor(std::vector<ParameterDescriptor>&& descriptors,
                                           const std::string& name) = delete;

// Descriptors for bare names: unit unknown, any value accepted (models that declare no ranges).
std::vector<ParameterDescriptor> unbounded_descriptors(const std::vector<std::string>& names);

}  // namespace demfit::identify
