#pragma once
// Catalogue of the physical effects the base LS-DYNA model can lack (issue #6): for each, the
// identified parameters that switch it on (names accepted by parameter_names(), --set, study
// variables and fixed overrides), their bounds, their off value (= the base model), the cases it
// applies to and the curves it changes. Physics: dem_core/contact_effects.hpp, docs/cases.md
// section "Effects". The diagnosis workflow (diagnose/) uses this as its list of candidates.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace demfit::cases {

struct EffectParameterInfo {
  std::string name;   // identified-parameter name (parameter_names())
  double lower = 0.0;
  double upper = 0.0;
  double off_value = 0.0;  // value at which the effect is absent
  std::string unit;        // "-" for dimensionless
};

struct EffectInfo {
  std::string name;
  std::string description;
  std::vector<EffectParameterInfo> parameters;
  std::vector<std::string> cases;   // "pellet_compression", "rotary_drum"
  std::vector<std::string> curves;  // simulated curves it changes; empty = all
};

// Every effect once, in a fixed order. Where bounds differ per case (cohesion: they follow the
// particle weight) the catalogue holds the widest; effects_for_case gives the case's own.
const std::vector<EffectInfo>& effect_catalogue();

// The effects that apply to a case ("pellet_compression" or "rotary_drum"), with that case's
// bounds: cohesion's follows the particle the simulation carries (the built-in case with
// `overrides` merged in, e.g. a drum's drum.scale_factor); throws std::runtime_error naming the
// case otherwise.
std::vector<EffectInfo> effects_for_case(const std::string& case_name, const nlohmann::json& overrides = {});

// The same for a whole case document (a case file after the study's overrides); its "case"
// field names the case. Throws std::runtime_error (one line) on a bad document.
std::vector<EffectInfo> effects_for_case_document(const nlohmann::json& case_document);

// Upper bound of surface_energy [J/m^2] for a particle of radius R [m] and density rho
// [kg/m^3] under gravity g [m/s^2]: the pull-off force 1.5 pi gamma R* of two equal spheres
// (R* = R/2) equals 5 particle weights, gamma = 5 m g / (0.75 pi R) = (80/9) rho g R^2.
double cohesion_surface_energy_bound(double radius, double density, double gravity = 9.81);

}  // namespace demfit::cases
