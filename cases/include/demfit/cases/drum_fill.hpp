#pragma once
// The drum fill amount rule (see FillBy in case_spec.hpp), exposed for tests and reports:
// N0 original particles from the case's fill amount, then the coarse count of Table 2.
#include "demfit/cases/case_spec.hpp"

namespace demfit::cases {

struct DrumFillAmount {
  double original_count = 0.0;       // N0 (before rounding) [-]
  long long coarse_count = 0;        // particles simulated at drum.scale_factor [-]
  double original_total_mass = 0.0;  // M0 [kg]
};

// Throws std::runtime_error unless spec.kind == rotary_drum, or when the fill holds less than
// one coarse particle.
DrumFillAmount drum_fill_amount(const CaseSpec& spec);

}  // namespace demfit::cases
