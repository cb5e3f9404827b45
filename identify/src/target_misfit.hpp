#pragma once
// Internal: how far the best run is from each target, in the curve's own units, so a result
// can be compared with figures quoted elsewhere (e.g. the source's surface metrics).
#include <vector>

#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify::detail {

struct TargetMisfit {
  bool available = false;  // false when the run lacks the curve or it cannot be compared
  double rms = 0.0;        // y units (see target_misfit)
  double area = -1.0;      // profile_area targets: x units x y units (mm^2 for mm curves); else < 0
};

// mse: RMS of (simulated - target) y at the target abscissae (simulated interpolated, ends held
// flat). curve_mapping: RMS y-distance of the matched stations. profile_area: the profiles as
// piecewise linear z(x) over their common x-range (demfit::imaging's metrics, exact): RMS
// distance sqrt((1/L) integral (f - G)^2 dx) and differing area integral |f - G| dx.
std::vector<TargetMisfit> target_misfits(const std::vector<TargetSpec>& targets, const CurveSet& curves);

}  // namespace demfit::identify::detail
