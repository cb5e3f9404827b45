#pragma once
// LIGGGHTS 3.8 input snippet of an identified Hertz–Mindlin answer (`demfit export --liggghts`):
// the material fixes (fix property/global youngsModulus, poissonsRatio, coefficientRestitution,
// coefficientFriction, coefficientRollingFriction, and cohesionEnergyDensity when cohesion is on)
// and the pair_style gran line, with the wall model in the variable demfit_wall_model for the
// user's fix wall/gran. dem_core's Hertz–Mindlin law is LIGGGHTS' `model hertz tangential history`
// (dem_core/contact_law_hertz.hpp), with the case's cohesion (sjkr, sjkr2) and rolling (cdt, epsd2)
// models under their LIGGGHTS names (dem_core/parameters.hpp).
//
// Atom types: 1 = particles, 2 = walls (the wall material of wall_contact; a particle-wall value is
// the 1-2 entry of a type-pair matrix). Which case field fills which entry is a parameter-table row
// (found by its case-file field); the names, units and values in the snippet come from the rows.
//
// The lsdyna_linear law is refused: its NORMK/SHEARK springs scale with each particle's radius
// (k = NORMK K R_i, two springs in series) and its damping is a fraction of critical, while
// LIGGGHTS' linear model (hooke/stiffness) takes one fixed stiffness and damping per atom-type pair
// and its hertz model is nonlinear, so no LIGGGHTS input reproduces the identified contact.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/model.hpp"
#include "demfit/identify/reported_interval.hpp"

namespace demfit::cases {

// The study's variables by name: the answer's value and its 95 % interval (reported_interval.hpp;
// available = false when the study has none).
using IdentifiedVariables = std::map<std::string, identify::ReportedInterval>;

// The snippet for `base` (the study's resolved case) with the answer's parameters `answer`
// applied. `title` becomes the first comment line; control characters in it are blanked. Throws
// std::runtime_error with one line when the case's law is lsdyna_linear (see above).
std::string liggghts_snippet(const CaseSpec& base, const identify::ParameterSet& answer,
                             const IdentifiedVariables& identified, const std::string& title);

// The snippet of a study with several experiments (each its own case, e.g. one drum speed each),
// all given the same identified `answer`: the first experiment's snippet, when every experiment's
// LIGGGHTS commands are the same (one material). Throws std::runtime_error with one line naming
// two experiments and the first differing command otherwise.
std::string liggghts_snippet(const std::vector<std::pair<std::string, CaseSpec>>& experiments,
                             const identify::ParameterSet& answer, const IdentifiedVariables& identified,
                             const std::string& title);

}  // namespace demfit::cases
