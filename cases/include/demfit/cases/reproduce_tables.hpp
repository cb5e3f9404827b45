#pragma once
// Text tables of the paper reproduced by `demfit reproduce` (Markdown, so they paste into
// report.md unchanged).
#include <string>
#include <vector>

#include "demfit/cases/coarse_graining.hpp"

namespace demfit::cases {

// Table 2 for the drum's original powder (r0, rho0) at phi, for each s in `scales`, both models,
// with the note on the CVF radius. Radius in mm, volume in mm^3, mass in mg, density kg/m^3,
// total mass as a multiple of M0.
std::string format_table2(const OriginalParticle& original, double volume_fraction, const std::vector<double>& scales);

}  // namespace demfit::cases
