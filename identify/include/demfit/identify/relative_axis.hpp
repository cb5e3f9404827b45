#pragma once
// Relative x-axes for compression curves ("fill offset"): a real bed never holds
// exactly the simulated amount of powder, so its absolute volumes are shifted against the
// model's. A target may name a model curve with a suffix that re-expresses x from first contact:
//   "<curve>@from_contact"  x' = x_c - x   label "<quantity>_change_<unit>" (e.g. volume_change_cm3)
//   "<curve>@strain"        x' = (x_c - x) / x_c   label "volumetric_strain_1" (dimensionless)
// x_c is the x of the first point whose y exceeds kContactFraction of the curve's largest |y|
// (first contact of the piston with the bed); points before it are dropped. The measured curve
// must be given on the same axis, from its own first contact (docs/study_format.md).
#include <memory>
#include <set>
#include <string>

#include "demfit/identify/model.hpp"

namespace demfit::identify {

inline constexpr double kContactFraction = 0.01;

// The derived curve, or throws std::runtime_error naming the curve when there is no contact.
Curve relative_axis_curve(const Curve& curve, const std::string& axis, const std::string& name);

// Wraps a model and adds the derived curves named in `requested` ("pressure_volume@strain", ...).
class RelativeAxisModel final : public Model {
 public:
  RelativeAxisModel(std::unique_ptr<Model> base, std::set<std::string> requested);
  std::vector<ParameterDescriptor> parameters() const override { return base_->parameters(); }
  ParameterSet default_parameters() const override { return base_->default_parameters(); }
  CurveSet evaluate(const ParameterSet& parameters, const EvaluationContext& context) const override;

 private:
  std::unique_ptr<Model> base_;
  std::set<std::string> requested_;
};

}  // namespace demfit::identify
