// The effects catalogue (see effect_catalogue.hpp; physics in dem_core/contact_effects.hpp and
// docs/cases.md "Effects").
#include "demfit/cases/effect_catalogue.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>

#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/coarse_graining.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/dem_core/hertz_cohesion.hpp"

namespace demfit::cases {
namespace {

// Case-kind names from the registry (case_registry.cpp).
const char* const kPellet = case_kind_row(CaseKind::pellet_compression).name;
const char* const kDrum = case_kind_row(CaseKind::rotary_drum).name;

// Pull-off force at the cohesion bound, in weights of the simulated particle. Pellet: five.
// Drum: one — above it the bed stops flowing and slumps as a cohesive block (s = 4 drum at
// 30 rpm: 0.57 weights lift the surface by 30 mm at the wall, 0.29 weights by 3 mm), a regime
// where the surface jumps rather than follows the parameter (docs/cases.md "Effects").
constexpr double kPelletCohesionWeights = 5.0;
constexpr double kDrumCohesionWeights = 1.0;

// An effect parameter with the FITTING range [lower, upper]: unit and off value come from its
// parameter-table row, and the range must lie inside the row's valid range (a logic error
// otherwise). Every range below is narrower than the valid one, for the reason given there.
EffectParameterInfo fitting(const char* name, double lower, double upper) {
  const ParameterRow* row = find_parameter(name);
  if (!row || !row->is_effect || !row->valid.contains_interval(lower, upper))
    throw std::logic_error(std::string("effect catalogue: '") + name +
                           "' is no effect row or its fitting range lies outside its valid range");
  return {name, lower, upper, row->off_value, row->unit};
}

// Cohesion upper bound of a case, from the particle the simulation carries: the pellet's own,
// the drum's coarse-grained one (SCG of scale s has radius s R0, so its bound is s^2 times the
// original's: the same range of cohesion-to-weight ratio at every scale).
double case_cohesion_bound(const CaseSpec& spec) {
  switch (spec.kind) {
    case CaseKind::rotary_drum: {
      const CoarseParticle p = coarse_grain(spec.drum.coarse_graining, spec.drum.scale_factor,
                                            spec.drum.volume_fraction, {spec.material.radius, spec.material.density});
      return cohesion_surface_energy_bound(p.radius, p.density, kDrumCohesionWeights);
    }
    case CaseKind::pellet_compression:
    case CaseKind::mesh_container:  // the simulated particle is the case's own, as in the pellet
      return cohesion_surface_energy_bound(spec.material.radius, spec.material.density, kPelletCohesionWeights);
  }
  throw std::logic_error("effect catalogue: a CaseKind without a cohesion bound");
}

EffectInfo cohesion(double upper) {
  return {"cohesion",
          "constant JKR-like pull-off force F_c = 1.5 pi gamma R* while particles (or a particle and a wall) "
          "overlap; the contact breaks at zero overlap (upper bound: F_c of two equal simulated spheres = " +
              std::to_string(static_cast<int>(kPelletCohesionWeights)) + " particle weights in the pellet, " +
              std::to_string(static_cast<int>(kDrumCohesionWeights)) + " in the drum)",
          {fitting("surface_energy", 0.0, upper)},
          {kPellet, kDrum},
          {}};
}

// The effects of case `case_name`, each with `cases` = {case_name}.
std::vector<EffectInfo> build(double cohesion_upper, const std::string& case_name) {
  std::vector<EffectInfo> all;
  all.push_back(
      {"plasticity",
       "Walton-Braun hysteretic normal spring: unloading stiffness k2 = ratio k1, delta0 = delta_max (1 - k1/k2); "
       "undamped restitution 1/sqrt(ratio). Shows mainly on unloading (pellet.unload = true, curve "
       "pressure_volume_cycle); contacts that unload during rearrangement change the loading curve too",
       // Up to 4 (head-on restitution 0.5) of the valid 100: the pellet cycle resolves that range.
       {fitting("unloading_stiffness_ratio", 1.0, 4.0)},
       {kPellet},
       {}});
  all.push_back(cohesion(cohesion_upper));
  all.push_back({"hertz_stiffness",
                 "nonlinear normal spring F = k_n d_ref (delta/d_ref)^n, d_ref = 0.01 R* (equal to the linear law at "
                 "1 % of R*); n = 1.5 is the Hertzian shape",
                 // Up to the Hertzian shape 1.5 of the valid 2.
                 {fitting("stiffness_exponent", 1.0, 1.5)},
                 {kPellet, kDrum},
                 {}});
  all.push_back({"wall_friction",
                 "particle-wall sliding friction (wall FRICS): Janssen effect in the pellet cylinder (the bottom plate "
                 "carries less than the piston), drag of the bed by the drum wall",
                 // Friction coefficients of granular materials: up to 0.6 (valid: any >= 0).
                 {fitting("wall_frics", 0.0, 0.6)},
                 {kPellet, kDrum},
                 {}});
  all.push_back({"rolling_resistance",
                 "constant-torque rolling friction between particles (FRICR; acts only with FRICS > 0)",
                 {fitting("fricr", 0.0, 0.3)},
                 {kPellet, kDrum},
                 {}});
  all.push_back(
      {"polydispersity",
       "radii uniform in [R(1 - s), R(1 + s)] at the same solid volume (the drum's coarse-grained radius gets "
       "the same relative spread); changes the fill, which is regenerated and cached per spread",
       // Up to 0.25, inside the valid 0.3 (the drum lattice limit).
       {fitting("radius_spread", 0.0, 0.25)},
       {kPellet, kDrum},
       {}});
  std::erase_if(
      all, [&](const EffectInfo& e) { return std::find(e.cases.begin(), e.cases.end(), case_name) == e.cases.end(); });
  for (EffectInfo& e : all) e.cases = {case_name};
  return all;
}

// ---- Hertz–Mindlin cases (dem_core/contact_law_hertz.hpp): the law's own options.

// Fitting range of the SJKR cohesion energy density [J/m^3]: up to 1e5 (k_c pi (2 R delta -
// delta^2) at 1e5 holds a 1 mm sphere of 2500 kg/m^3 on a wall with 6 of its weights at an
// overlap of 0.1 % of R: strongly cohesive), lowered to just below the time step's limit for the
// case's particle and wall materials (hertz_cohesion_limit) when that is smaller, so the upper
// end always runs.
constexpr double kHertzCohesionUpper = 1.0e5;

double hertz_cohesion_upper(const CaseSpec& spec) {
  const double particle =
      (1.0 - spec.material.poisson_ratio * spec.material.poisson_ratio) / spec.material.youngs_modulus;
  const double wall = spec.wall.hertz_normal_compliance();
  const dem_core::CohesionModel model = spec.contact.cohesion_model;
  const double limit = std::min(dem_core::hertz_cohesion_limit(1.0 / (2.0 * particle), model, false),
                                dem_core::hertz_cohesion_limit(1.0 / (particle + wall), model, true));
  return std::min(kHertzCohesionUpper, 0.99 * limit);
}

const char* rolling_text(dem_core::RollingModel model) {
  switch (model) {
    case dem_core::RollingModel::constant_torque:
      return "constant-torque rolling friction between particles (cdt: M_r = FRICR F_n R*; acts only with "
             "FRICS > 0)";
    case dem_core::RollingModel::elastic_plastic:
      return "epsd2 rolling spring between particles (k_r = k_t R*^2, capped at FRICR F_n R*; acts only with "
             "FRICS > 0)";
  }
  return "";
}

// A "released constraint": a parameter the case fixes (not an effect) set free over
// [lower, upper]; its off value is the case's own value (the base model), and the range is
// widened to contain it. A logic error when the row does not exist or the range leaves its valid one.
EffectParameterInfo released(const char* name, double lower, double upper, const CaseSpec& spec) {
  const ParameterRow* row = find_parameter(name);
  if (!row || !row->applies_to(spec.law))
    throw std::logic_error(std::string("effect catalogue: '") + name + "' is no parameter of the case's law");
  const double fixed = row->get(spec);
  lower = std::min(lower, fixed);
  upper = std::max(upper, fixed);
  if (!row->valid.contains_interval(lower, upper))
    throw std::logic_error(std::string("effect catalogue: the released range of '") + name +
                           "' lies outside its valid range");
  return {name, lower, upper, fixed, row->unit};
}

// The Hertz law's candidates for a drum case (the only kind that runs Hertz–Mindlin).
std::vector<EffectInfo> hertz_effects(const CaseSpec& spec) {
  const std::string name = case_kind_row(spec.kind).name;
  std::vector<EffectInfo> all;
  all.push_back({"cohesion",
                 std::string("SJKR cohesion: attractive normal force k_c A while particles (or a particle and a wall) "
                             "overlap, A the ") +
                     (spec.contact.cohesion_model == dem_core::CohesionModel::sjkr
                          ? "area of the spheres' intersection circle (sjkr)"
                          : "sjkr2 area 2 pi delta 2R*") +
                     "; the contact breaks at zero overlap",
                 {fitting("cohesion_energy_density", 0.0, hertz_cohesion_upper(spec))},
                 {name},
                 {}});
  if (!spec.wall_friction_as_particles)
    all.push_back({"wall_friction",
                   "particle-wall sliding friction (wall FRICS): drag of the bed by the drum wall",
                   {fitting("wall_frics", 0.0, 0.6)},
                   {name},
                   {}});
  else  // released from the tie: the wall's FRICS from 0 to twice the particles'
    all.push_back({"wall_friction",
                   "particle-wall sliding friction released from the particles' value (the case ties them): wall "
                   "FRICS = ratio x particle FRICS, drag of the bed by the drum wall",
                   {fitting("wall_friction_ratio", 0.0, 2.0)},
                   {name},
                   {}});
  all.push_back(
      {"rolling_resistance", rolling_text(spec.contact.rolling_model), {fitting("fricr", 0.0, 0.3)}, {name}, {}});
  // Released: the case fixes e (e.g. 0.3 for the GranuDrum powder); free over the range where
  // restitution-based damping is meaningful for granular media (0.05 heavily damped to 0.95
  // nearly elastic).
  all.push_back({"restitution",
                 "coefficient of restitution of pairs and walls released from the case's fixed value (Hertz "
                 "damping; off value = the case's e)",
                 {released("restitution", 0.05, 0.95, spec)},
                 {name},
                 {}});
  return all;
}

}  // namespace

double cohesion_surface_energy_bound(double radius, double density, double weights, double gravity) {
  const double weight = density * sphere_volume(radius) * gravity;
  // 1.5 pi gamma R* = weights * m g with R* = R/2 (two equal spheres).
  return weights * weight / (1.5 * std::numbers::pi * 0.5 * radius);
}

std::vector<EffectInfo> effects_for_case(const std::string& case_name, const nlohmann::json& overrides) {
  if (!find_case_kind(case_name))
    throw std::runtime_error("effects_for_case: case '" + case_name + "' is unknown: use " + case_kind_names());
  return effects_for_case(resolve_case(case_name, overrides, {}));
}

std::vector<EffectInfo> effects_for_case(const CaseSpec& spec) {
  switch (spec.law) {  // each law has its own options (dem_core/contact_laws.hpp)
    case dem_core::ContactLawKind::lsdyna_linear:
      return build(case_cohesion_bound(spec), case_kind_row(spec.kind).name);
    case dem_core::ContactLawKind::hertz_mindlin:
      return hertz_effects(spec);
  }
  throw std::logic_error("effect catalogue: a ContactLawKind without effects");
}

}  // namespace demfit::cases
