#pragma once
// Physical parameters at the API (docs/spec.md section 1). Derived numbers (springs, damping
// coefficients, time steps) are computed inside dem_core from these.
// LS-DYNA names (NORMK, SHEARK, ...) appear here only as field names of the input structs,
// because they are the quantities the user identifies; the kernel uses physical names.

#include <cstddef>
#include <stdexcept>
#include <utility>

namespace demfit::dem_core {

/// Which contact law the pair/wall loops are instantiated with (chosen once per simulation;
/// the loops are templates on the law type, so there is no per-contact dispatch).
enum class ContactLawKind {
  lsdyna_linear,  ///< LS-DYNA *CONTROL_DISCRETE_ELEMENT linear spring-dashpot (docs/spec.md 1)
  hertz_mindlin,  ///< Hertz normal + Mindlin no-slip tangential, restitution-based damping
};

/// Contact area of the SJKR cohesion of the Hertz–Mindlin law (LIGGGHTS `cohesion sjkr` /
/// `cohesion sjkr2`; contact_law_hertz.hpp).
enum class CohesionModel {
  sjkr,   ///< A = pi a^2, a = radius of the circle where the two undeformed spheres intersect
  sjkr2,  ///< A = 2 pi delta (2 R*) (LIGGGHTS sjkr2 documentation)
};

/// Rolling resistance of the Hertz–Mindlin law (LIGGGHTS `rolling_friction cdt` / `epsd2`).
enum class RollingModel {
  constant_torque,  ///< cdt: M_r = -mu_r |F_n| R* omega_rel/|omega_rel| (docs/spec.md 1); both laws
  elastic_plastic,  ///< epsd2: incremental rolling spring k_r = k_t R*^2, capped at mu_r R* F_n
};

/// The models' names in case files and messages (LIGGGHTS' names), one row per value.
inline constexpr std::pair<CohesionModel, const char*> kCohesionModels[] = {{CohesionModel::sjkr, "sjkr"},
                                                                            {CohesionModel::sjkr2, "sjkr2"}};
inline constexpr std::pair<RollingModel, const char*> kRollingModels[] = {{RollingModel::constant_torque, "cdt"},
                                                                          {RollingModel::elastic_plastic, "epsd2"}};
/// The name of `model` in `models` (kCohesionModels, kRollingModels); a logic error without a row.
template <class Model, std::size_t N>
const char* model_name(const std::pair<Model, const char*> (&models)[N], Model model) {
  for (const auto& [m, name] : models)
    if (m == model) return name;
  throw std::logic_error("a contact model without a name row (dem_core/parameters.hpp)");
}

/// Particle material (solid spheres: m = rho 4/3 pi R^3, I = 2/5 m R^2).
struct Material {
  double bulk_modulus = 1.0e9;  ///< K [Pa]; LS-DYNA spring k_i = NORMK * K * R_i
  double density = 2500.0;      ///< true (solid) density rho [kg/m^3]
  double poisson_ratio = 0.3;   ///< nu [-]; used only by Hertz–Mindlin (E = 3K(1-2nu))
};

/// Particle–particle contact parameters, LS-DYNA *CONTROL_DISCRETE_ELEMENT semantics, with the
/// LS-DYNA defaults. One set for the whole simulation (as in LS-DYNA).
struct ContactParameters {
  double normk = 0.01;        ///< NORMK [-]: particle spring k_i = NORMK*K_i*R_i; pair = springs in series
  double sheark = 2.0 / 7.0;  ///< SHEARK [-]: tangential spring k_t = SHEARK*k_n
  double ndamp = 0.0;         ///< NDAMP [-]: normal damping as a fraction of critical, in [0,1)
  double tdamp = 0.0;         ///< TDAMP [-]: tangential damping as a fraction of critical, in [0,1)
  double frics = 0.0;         ///< FRICS [-]: static friction; FRICS = 0 disables ALL particle rotation
                              ///<   (LS-DYNA behaviour: no rotational DOF, no torques, no rolling friction)
  double fricd = -1.0;        ///< FRICD [-]: dynamic friction; negative means "same as FRICS" (LS-DYNA default)
  double dc = 0.0;            ///< DC [s/m]: mu = FRICD + (FRICS-FRICD) exp(-DC |v_t|)
  double fricr = 0.0;         ///< FRICR [-]: rolling friction, constant-torque model
  double restitution = 1.0;   ///< e [-], Hertz–Mindlin only (the linear law uses NDAMP/TDAMP)

  // ---- Effects library (linear law only, pairs AND walls; see contact_effects.hpp).
  // Each is off at its default value; with all three off the simulation takes exactly the code
  // path of the plain LS-DYNA law (bit-identical results, no extra cost).
  /// Walton–Braun (1986) plasticity: unloading stiffness k2 = ratio * k1 [-], ratio >= 1;
  /// 1 = elastic (off). Undamped head-on restitution e = 1/sqrt(ratio).
  double unloading_stiffness_ratio = 1.0;
  /// Cohesion: surface energy gamma [J/m^2] >= 0 of a constant JKR-like pull-off force
  /// F_c = 1.5 pi gamma R* (walls: R* = R), attractive, acting only while overlap > 0; 0 = off.
  double surface_energy = 0.0;
  /// Nonlinear normal stiffness exponent n in [1, 2]: F_el = k_n d_ref (delta/d_ref)^n with
  /// d_ref = 0.01 R*; 1 = linear (off), 1.5 = Hertzian shape.
  double stiffness_exponent = 1.0;

  // ---- Hertz–Mindlin only (contact_law_hertz.hpp); refused with the linear law unless off.
  /// SJKR cohesion energy density k_c [J/m^3] >= 0: attractive normal force k_c A while the
  /// bodies overlap (A from `cohesion_model`); 0 = off (the plain Hertz–Mindlin law).
  double cohesion_energy_density = 0.0;
  CohesionModel cohesion_model = CohesionModel::sjkr;
  /// cdt (default, the constant torque of FRICR / wall FRICD) or epsd2 (rolling spring).
  RollingModel rolling_model = RollingModel::constant_torque;

  /// FRICD with the LS-DYNA default resolved (FRICD unset => FRICS).
  [[nodiscard]] double dynamic_friction() const { return fricd < 0.0 ? frics : fricd; }
  [[nodiscard]] bool rotation_enabled() const { return frics > 0.0; }
  /// True when any effect of the effects library is switched on (selects the effects law).
  [[nodiscard]] bool effects_enabled() const {
    return unloading_stiffness_ratio != 1.0 || surface_energy != 0.0 || stiffness_exponent != 1.0;
  }
};

/// Particle-to-wall parameters (*DEFINE_DE_TO_SURFACE_COUPLING card 2 semantics).
/// Wall springs: k_n,w = SFP*NORMK*K*R (no series partner), k_t,w = SHEARK*k_n,w.
struct WallContactParameters {
  double frics = 0.0;  ///< FRICS [-]: sliding (Coulomb) friction particle–wall
  double fricd = 0.0;  ///< FRICD [-]: ROLLING friction particle–wall (its meaning on this card)
  double damp = 0.0;   ///< DAMP [-]: damping fraction of critical, normal AND tangential, c = 2 DAMP sqrt(m k)
  double sfp = 1.0;    ///< SFP [-]: scale factor on the wall normal spring
  // ---- Hertz–Mindlin only (ignored by the linear law). The wall's elastic material: the wall
  // adds its compliances (1 - nu_w^2)/E_w and (2 - nu_w)/G_w to the particle's, as a second
  // body of a Hertz pair (E* = 1/sum((1-nu^2)/E), G* = 1/sum((2-nu)/G)). 0 = rigid wall.
  double youngs_modulus = 0.0;  ///< E_w [Pa]; 0 = rigid (adds no compliance)
  double poisson_ratio = 0.3;   ///< nu_w [-], in (-1, 0.5)
  /// Normal and shear compliances the wall adds to a Hertz contact [1/Pa] (0 for a rigid wall).
  [[nodiscard]] double hertz_normal_compliance() const {
    return youngs_modulus > 0.0 ? (1.0 - poisson_ratio * poisson_ratio) / youngs_modulus : 0.0;
  }
  [[nodiscard]] double hertz_shear_compliance() const {
    return youngs_modulus > 0.0 ? (2.0 - poisson_ratio) * 2.0 * (1.0 + poisson_ratio) / youngs_modulus : 0.0;
  }
};

/// Throw std::runtime_error (one line naming the field) if a parameter is out of range or NaN.
void validate(const Material& material);
void validate(const ContactParameters& parameters);
void validate(const WallContactParameters& parameters);

}  // namespace demfit::dem_core
