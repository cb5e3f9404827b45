#pragma once
// Tangential and rolling parts shared by the contact laws (SPEC 1). Each part is a small value
// type; a law composes a normal part with these. Header-only so the templated loops inline them.
#include <cmath>

#include "demfit/dem_core/contact_geometry.hpp"

namespace demfit::dem_core {

/// Incremental tangential spring with viscous damping and a Coulomb limit.
/// xi is rotated into the current tangent plane (magnitude kept), incremented by v_t dt; the force
/// F_t = -k_t xi - c_t v_t is limited to mu |F_n| with mu = FRICD + (FRICS-FRICD) exp(-DC |v_t|);
/// while sliding the spring is scaled back so that it reproduces the limited force.
struct CoulombTangentialSpring {
  double static_friction = 0.0;   ///< FRICS [-]
  double dynamic_friction = 0.0;  ///< FRICD [-]
  double decay = 0.0;             ///< DC [s/m]

  /// stiffness k_t [N/m], damping c_t [N s/m], normal_force |F_n| [N]; `displacement` is the
  /// contact history's xi_t [m], updated. Returns the force on i.
  Vec3 evaluate(const ContactGeometry& g, double stiffness, double damping, double normal_force, Vec3& displacement,
                double dt, double& elastic_energy) const {
    if (static_friction <= 0.0 && dynamic_friction <= 0.0) {
      displacement = {};
      return {};
    }
    const Vec3& n = g.normal;
    const Vec3 v_t = g.contact_velocity - dot(g.contact_velocity, n) * n;
    // Rotate the stored elongation into the current tangent plane, keeping its length.
    Vec3 xi = displacement;
    const double old_length2 = norm2(xi);
    if (old_length2 > 0.0) {
      xi -= dot(xi, n) * n;
      const double new_length2 = norm2(xi);
      if (new_length2 > 0.0) xi *= std::sqrt(old_length2 / new_length2);
    }
    xi += v_t * dt;
    Vec3 f_t = -stiffness * xi - damping * v_t;
    // exp only when the friction really depends on the slip speed (DC > 0 and FRICS != FRICD).
    const double mu = (decay > 0.0 && static_friction != dynamic_friction)
                          ? dynamic_friction + (static_friction - dynamic_friction) * std::exp(-decay * norm(v_t))
                          : static_friction;
    const double limit = mu * std::fabs(normal_force);
    const double f_t_length2 = norm2(f_t);
    if (f_t_length2 > limit * limit) {
      f_t *= limit / std::sqrt(f_t_length2);
      // Sliding: the spring holds exactly what the limited force leaves after damping.
      xi = stiffness > 0.0 ? (-1.0 / stiffness) * (f_t + damping * v_t) : Vec3{};
    }
    displacement = xi;
    elastic_energy += 0.5 * stiffness * norm2(xi);
    return f_t;
  }
};

/// Constant-torque rolling resistance (SPEC 1): M_r = -mu_r |F_n| R* omega_rel/|omega_rel|,
/// limited so that it cannot reverse omega_rel within one step:
/// |M_r| dt (1/I_i + 1/I_j) <= |omega_rel|.
struct ConstantTorqueRolling {
  double coefficient = 0.0;  ///< FRICR (pairs) or wall FRICD (walls) [-]

  Vec3 evaluate(const ContactGeometry& g, double normal_force, double dt) const {
    if (coefficient <= 0.0) return {};
    const Vec3& w = g.relative_angular_velocity;
    const double w_length = norm(w);
    if (w_length <= 0.0) return {};
    double magnitude = coefficient * std::fabs(normal_force) * g.effective_radius;
    const double stopping = w_length / (dt * g.inverse_inertia_sum);
    if (magnitude > stopping) magnitude = stopping;
    return (-magnitude / w_length) * w;
  }
};

}  // namespace demfit::dem_core
