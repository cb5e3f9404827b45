#pragma once
// A candidate physical effect the base model may lack. An effect is data: the extra
// model parameters it adds (each with bounds and the "off" value at which the effect vanishes)
// and the simulated curves it changes. The model must accept those parameters; with every effect
// parameter at its off value it must reproduce the base model.
#include <string>
#include <vector>

#include "demfit/identify/parameter_descriptor.hpp"

namespace demfit::diagnose {

// name, fitting bounds [lower, upper] in model units, off value (inside the bounds), unit: the
// type of the cases' effect catalogue too (identify/parameter_descriptor.hpp).
using EffectParameter = identify::EffectParameter;

struct EffectCandidate {
  std::string name;                         // short name used in reports ("stiffening")
  std::string description;                  // one line, human
  std::vector<EffectParameter> parameters;  // extra parameters (at least one)
  std::vector<std::string> curves;          // simulated curves it applies to; empty = all
};

// Throws std::runtime_error naming the candidate and field if a candidate is inconsistent
// (no parameters, off value outside its bounds, empty bounds, duplicate names).
void validate_candidates(const std::vector<EffectCandidate>& candidates);

// Candidates understood by AnalyticEffectsModel (analytic_effects_model.hpp): stiffening,
// toe_shift, yield_drop. The ripple term of that model is deliberately NOT a candidate (it is
// a non-physical artefact used as the "unexplained residual" control). DEM candidates will come
// from cases/ (they need dem_core effects).
std::vector<EffectCandidate> analytic_effect_candidates();

// The candidates of `candidates` whose names are in the comma-separated `list` (spaces
// ignored); throws naming an unknown name and listing the known ones.
std::vector<EffectCandidate> select_candidates(const std::vector<EffectCandidate>& candidates, const std::string& list);

}  // namespace demfit::diagnose
