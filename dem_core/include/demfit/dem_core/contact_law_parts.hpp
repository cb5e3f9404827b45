#pragma once
// Tangential and rolling parts shared by the contact laws (docs/spec.md 1). Each part is a small value
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
  /// Always inlined into the contact loops (per contact per step; see pair_geometry).
  [[gnu::always_inline]] Vec3 evaluate(const ContactGeometry& g, double stiffness, double damping, double normal_force,
                                       Vec3& displacement, double dt, double& elastic_energy) const {
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

/// Constant-torque rolling resistance (docs/spec.md 1): M_r = -mu_r |F_n| R* omega_rel/|omega_rel|,
/// limited so that it cannot reverse omega_rel within one step:
/// |M_r| dt (1/I_i + 1/I_j) <= |omega_rel|.
struct ConstantTorqueRolling {
  double coefficient = 0.0;  ///< FRICR (pairs) or wall FRICD (walls) [-]

  [[gnu::always_inline]] Vec3 evaluate(const ContactGeometry& g, double normal_force, double dt) const {
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

/// History of a contact with the epsd2 rolling spring: the tangential spring and the rolling
/// torque on i (48 bytes per contact, 24 more than ContactHistory; only the epsd2 law carries it).
/// Both are of the first body relative to the second: negated when a pair's members swap.
struct RollingSpringHistory {
  Vec3 tangential_displacement{};  ///< incremental tangential spring elongation xi_t [m]
  Vec3 rolling_torque{};           ///< rolling spring torque M_r on i [N·m]
};

/// Elastic–plastic spring rolling resistance without damping (LIGGGHTS `rolling_friction epsd2`;
/// Iwashita & Oda 1998, J. Eng. Mech. 124:285): rolling stiffness k_r = k_t R*^2 with k_t the
/// contact's tangential stiffness; incremental torque M_r <- M_r - k_r omega_roll dt, omega_roll
/// = omega_i - omega_j projected on the tangent plane (the twist about the normal does not load
/// the spring: LIGGGHTS' torsionTorque = off); |M_r| <= mu_r R* |F_n| (full mobilisation, the
/// constant torque of cdt), F_n the repulsive normal force. The stored torque is turned into the
/// current tangent plane with its length kept, as the tangential spring is.
/// The rolling mode is slower than the tangential one the time step covers: for two equal spheres
/// k_r (1/I_i + 1/I_j) = 1.25 k_t/m against about 7 k_t/m.
struct ElasticPlasticRolling {
  double coefficient = 0.0;  ///< FRICR (pairs) or wall FRICD (walls) [-]

  /// tangential_stiffness k_t [N/m], normal_force F_n [N]; `torque` is the history's M_r, updated.
  /// Returns the torque on i [N·m].
  Vec3 evaluate(const ContactGeometry& g, double tangential_stiffness, double normal_force, Vec3& torque,
                double dt) const {
    if (coefficient <= 0.0) {
      torque = {};
      return {};
    }
    const Vec3& n = g.normal;
    Vec3 m = torque;
    const double old_length2 = norm2(m);
    if (old_length2 > 0.0) {
      m -= dot(m, n) * n;
      const double new_length2 = norm2(m);
      if (new_length2 > 0.0) m *= std::sqrt(old_length2 / new_length2);
    }
    const Vec3& w = g.relative_angular_velocity;
    const Vec3 rolling = w - dot(w, n) * n;
    const double r = g.effective_radius;
    m -= (tangential_stiffness * r * r * dt) * rolling;
    const double limit = coefficient * r * std::fabs(normal_force);
    const double length2 = norm2(m);
    if (length2 > limit * limit) m *= limit / std::sqrt(length2);
    torque = m;
    return m;
  }
  /// Energy of the rolling spring |M_r|^2/(2 k_r) [J] (0 without stiffness).
  [[nodiscard]] static double energy(const ContactGeometry& g, double tangential_stiffness, const Vec3& torque) {
    const double k_r = tangential_stiffness * g.effective_radius * g.effective_radius;
    return k_r > 0.0 ? 0.5 * norm2(torque) / k_r : 0.0;
  }
};

}  // namespace demfit::dem_core
