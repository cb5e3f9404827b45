#pragma once
// SJKR cohesion of the Hertz–Mindlin law (LIGGGHTS `cohesion sjkr` and `cohesion sjkr2`, as their
// documentation pages gran_cohesion_sjkr.html and gran_cohesion_sjkr2.html state them):
//   F_coh = k_c A, attractive along the normal, k_c the cohesion energy density [J/m^3],
// acting only while the bodies overlap (the pair loop sees only overlapping pairs, so the contact
// breaks at zero overlap). Contact area A:
//   sjkr:  A = pi a^2, a the radius of the circle where the two undeformed spheres intersect
//          (the rim of the overlap lens; sphere-sphere intersection, e.g. Weisstein, MathWorld):
//          a^2 = (d^2 - (R_i - R_j)^2) ((R_i + R_j)^2 - d^2) / (4 d^2), d = R_i + R_j - delta.
//          A sphere on a wall is the limit R_j -> infinity: a^2 = 2 R delta - delta^2. A cylinder
//          wall is taken as its tangent plane at the contact point (a drum is many particle radii
//          across, so its curvature changes a^2 by a relative R/R_drum, below the model's accuracy).
//   sjkr2: A = 2 pi delta (2 R*), the formula of the LIGGGHTS sjkr2 page (walls: R* = R, the wall
//          convention of LIGGGHTS' Hertz law). For small overlaps the sjkr lens gives 2 pi R* delta,
//          so sjkr2 pulls twice as hard. LIGGGHTS 3.8's code (cohesion_model_sjkr2.h) takes
//          2 pi R delta on a wall, half of this: demfit's sjkr2 wall cohesion is twice LIGGGHTS'.
// The Coulomb limit and the rolling torque use the REPULSIVE (Hertz) part of the normal force, as
// LIGGGHTS does by default (its tangential_reduce = off; `on` would subtract the cohesion from the
// force the friction limit sees): cohesion presses the surfaces together and so does not cancel
// the friction a contact can carry.
#include <cmath>
#include <numbers>

#include "demfit/dem_core/contact_geometry.hpp"
#include "demfit/dem_core/parameters.hpp"

namespace demfit::dem_core {

/// a^2 [m^2] of the circle where spheres of radii R_i, R_j [m] intersect at overlap delta [m]:
/// (d^2 - D^2)(S^2 - d^2)/(4 d^2) with S = R_i + R_j, D = R_i - R_j, d = S - delta, written as
/// (d - D)(d + D) delta (S + d)/(4 d^2) so that no difference of nearly equal numbers is formed.
inline double sphere_intersection_radius2(double first_radius, double second_radius, double overlap) {
  const double sum = first_radius + second_radius;
  const double difference = first_radius - second_radius;
  const double d = sum - overlap;
  return (d - difference) * (d + difference) * overlap * (sum + d) / (4.0 * d * d);
}

/// a^2 [m^2] of a sphere of radius R [m] cut by a plane at depth delta [m]: 2 R delta - delta^2.
inline double plane_intersection_radius2(double radius, double overlap) { return overlap * (2.0 * radius - overlap); }

/// Contact area A [m^2] of `model` for contact `g` (g.second_radius = 0: a wall).
inline double sjkr_contact_area(CohesionModel model, const ContactGeometry& g) {
  switch (model) {
    case CohesionModel::sjkr: {
      const double a2 = g.second_radius > 0.0 ? sphere_intersection_radius2(g.first_radius, g.second_radius, g.overlap)
                                              : plane_intersection_radius2(g.first_radius, g.overlap);
      return std::numbers::pi * a2;
    }
    case CohesionModel::sjkr2:
      return 2.0 * std::numbers::pi * g.overlap * (2.0 * g.effective_radius);
  }
  return 0.0;
}

/// The cohesive part of the Hertz law: k_c and the area model.
struct SjkrCohesion {
  double energy_density = 0.0;  ///< k_c [J/m^3]; 0 = off
  CohesionModel model = CohesionModel::sjkr;

  /// Attractive force magnitude k_c A [N]; exactly 0 when off (nothing else is computed).
  [[nodiscard]] double force(const ContactGeometry& g) const {
    if (energy_density <= 0.0) return 0.0;
    return energy_density * sjkr_contact_area(model, g);
  }
};

/// Overlap, as a fraction of the particle radius, up to which the Hertz time step and the
/// small-strain Hertz law are meant to hold (the same 5 % the linear law's step plans for).
inline constexpr double kCohesionPlannedOverlap = 0.05;

/// Largest cohesion energy density [J/m^3] accepted for contacts of effective modulus E* [Pa]
/// (E* = 1/sum((1 - nu^2)/E)): two equal spheres (`wall` false) or a sphere on a plane (`wall`
/// true). Criterion: at the planned overlap delta_p = 5 % of the radius the cohesive force must
/// not exceed the Hertz elastic force 4/3 E* sqrt(R*) delta_p^(3/2), i.e. cohesion alone cannot
/// hold a contact deeper than delta_p. Then the cohesive "negative stiffness" dF_coh/ddelta
/// (about F_coh/delta, as A grows linearly in delta) stays below the Hertz tangent stiffness
/// 3/2 F_H/delta_p at delta_p, so the net normal stiffness stays between 0 and the Hertz one the
/// time step covers. Both forces scale as R^2, so the limit is a pure multiple of E*: sjkr pair
/// 0.0680 E*, sjkr2 pair 0.0336 E*, sjkr wall 0.0487 E*, sjkr2 wall 0.0237 E*.
inline double hertz_cohesion_limit(double effective_modulus, CohesionModel model, bool wall) {
  const double delta = kCohesionPlannedOverlap;  // radius 1: the ratio does not depend on R
  ContactGeometry g;
  g.overlap = delta;
  g.first_radius = 1.0;
  g.second_radius = wall ? 0.0 : 1.0;
  g.effective_radius = wall ? 1.0 : 0.5;
  const double hertz = 4.0 / 3.0 * effective_modulus * std::sqrt(g.effective_radius) * delta * std::sqrt(delta);
  return hertz / sjkr_contact_area(model, g);
}

}  // namespace demfit::dem_core
