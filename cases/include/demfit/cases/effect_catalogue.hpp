#pragma once
// Catalogue of the physical effects a case's base model can lack: for each, the identified
// parameters that switch it on (names accepted by parameter_names(), --set, study variables and
// fixed overrides), their bounds, their off value (= the base model), the cases it applies to
// and the curves it changes. The effects depend on the case's contact law: the LS-DYNA law's
// effects library (dem_core/contact_effects.hpp, docs/cases.md "Effects"), or for Hertz–Mindlin
// SJKR cohesion, wall and rolling friction and the released restitution (dem_core/
// contact_law_hertz.hpp, docs/cases.md "Hertz–Mindlin cohesion"). A "released" parameter is one
// the case fixes: its off value is the case's own value. The diagnosis workflow (diagnose/) uses
// this as its list of candidates.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/parameter_descriptor.hpp"

namespace demfit::cases {

// name, fitting range [lower, upper] (inside the parameter table's valid range), off value, unit:
// the type diagnose's effect candidates use too.
using EffectParameterInfo = identify::EffectParameter;

struct EffectInfo {
  std::string name;
  std::string description;
  std::vector<EffectParameterInfo> parameters;
  std::vector<std::string> cases;   // "pellet_compression", "rotary_drum"
  std::vector<std::string> curves;  // simulated curves it changes; empty = all
};

// The effects that apply to a case, in a fixed order, with that case's bounds: under the LS-DYNA
// law cohesion's follows the particle the simulation carries (e.g. a drum's coarse particle at
// drum.scale_factor); under Hertz–Mindlin it stops below the case's cohesion limit. `effects_for_case(name,
// overrides)`: the built-in case ("pellet_compression" or "rotary_drum") with `overrides` merged in; throws
// std::runtime_error naming an unknown case.
std::vector<EffectInfo> effects_for_case(const std::string& case_name, const nlohmann::json& overrides = {});
std::vector<EffectInfo> effects_for_case(const CaseSpec& spec);

// Upper bound of surface_energy [J/m^2] for a particle of radius R [m] and density rho
// [kg/m^3] under gravity g [m/s^2]: the pull-off force 1.5 pi gamma R* of two equal spheres
// (R* = R/2) equals `weights` particle weights, gamma = w m g / (0.75 pi R) = (16/9) w rho g R^2.
// The catalogue uses 5 weights for the pellet and 1 for the drum (effects_for_case).
double cohesion_surface_energy_bound(double radius, double density, double weights, double gravity = 9.81);

}  // namespace demfit::cases
