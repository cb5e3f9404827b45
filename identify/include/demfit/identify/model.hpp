#pragma once
// The only thing identify knows about a simulation: parameters in, named curves out.
// cases/ implements this for DEM cases; tests implement it with analytic curve families.
#include <map>
#include <string>
#include <vector>

#include "demfit/identify/parameter_descriptor.hpp"

namespace demfit::identify {

// One sampled response curve, e.g. pressure [MPa] against bed volume [cm3].
// Units are part of the labels ("volume_cm3", "pressure_MPa"), as in the CSV header.
struct Curve {
  std::string x_label;
  std::string y_label;
  std::vector<double> x;
  std::vector<double> y;
};

// A curve a model declares before any run: its name and its column labels (with units), so a
// study's targets are checked when it is loaded, not after the first simulation.
struct CurveDescriptor {
  std::string name;
  std::string x_label;
  std::string y_label;
  // [m] For a curve read from a picture of the model's own frame (a drum's free_surface_image):
  // the length the picture spans, which a photo target of that curve must span too, or its
  // millimetres are not the model's. 0 = not a picture curve.
  double picture_span = 0.0;
};

// Parameter values by name, in the units the model declares (SI unless the name says otherwise).
using ParameterSet = std::map<std::string, double>;

// Named curves produced by one evaluation ("pressure_volume", "torque", "free_surface", ...).
using CurveSet = std::map<std::string, Curve>;

struct EvaluationContext {
  int threads = 1;         // OpenMP threads this evaluation may use
  unsigned long seed = 0;  // study seed, for models with stochastic set-up (kept fixed per study)
};

class Model {
 public:
  virtual ~Model() = default;
  // Every parameter evaluate() accepts (anything else is an error), with its unit and valid range:
  // study bounds are checked against them before a study starts. A model that declares no ranges
  // returns unbounded_descriptors({names...}): any value, unit unknown.
  virtual std::vector<ParameterDescriptor> parameters() const = 0;
  // The names of parameters(), in its order (derived: one declaration per model).
  std::vector<std::string> parameter_names() const {
    std::vector<std::string> names;
    for (const ParameterDescriptor& d : parameters()) names.push_back(d.name);
    return names;
  }
  // Every curve evaluate() can return, with its labels. Empty = not declared (the study's targets
  // are then checked only at the initial point).
  virtual std::vector<CurveDescriptor> curves() const { return {}; }
  // Values used for parameters a study does not vary.
  virtual ParameterSet default_parameters() const = 0;
  // Runs one evaluation. Must be safe to call concurrently from several threads on one object.
  // Throws std::runtime_error on failure (instability, NaN...); the loop records and skips it.
  virtual CurveSet evaluate(const ParameterSet& parameters, const EvaluationContext& context) const = 0;
};

}  // namespace demfit::identify
