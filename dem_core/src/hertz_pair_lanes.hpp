#pragma once
// The Hertz–Mindlin pair law with constant-torque rolling (HertzMindlinLaw) computed for
// kPairLanes touching pairs at once, one pair per SIMD lane. One contact's law is a chain of
// dependent square roots and divisions (distance -> normal -> contact radius -> damping ->
// tangential spring -> Coulomb limit -> rolling limit) that out-of-order execution overlaps
// little with the next contact's; lanes run several chains side by side.
//
// Every lane performs the scalar code's operations (pair_geometry in contact_loops.hpp,
// HertzLaw::force, CoulombTangentialSpring::evaluate, ConstantTorqueRolling::evaluate) in the
// same order on IEEE doubles, and each branch becomes a select of the value the scalar branch
// would keep, so every lane's result is bit-identical to the scalar law's (no FMA contraction:
// -ffp-contract=off). Only the law's plain form is laned (hertz_lanes_apply): no cohesion, a
// friction limit without slip-speed decay, rotation on; other settings use the scalar loop.
#include <cstdint>

#include "contact_loops.hpp"
#include "demfit/dem_core/contact_law_hertz.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace demfit::dem_core {

inline constexpr int kPairLanes = 4;
using Lanes = double __attribute__((vector_size(sizeof(double) * kPairLanes)));
using LaneMask = std::int64_t __attribute__((vector_size(sizeof(double) * kPairLanes)));

struct LaneVec3 {
  Lanes x, y, z;
};

namespace lanes {

inline Lanes splat(double v) { return Lanes{} + v; }
inline Lanes sqrt(Lanes v) {
#if defined(__SSE2__)
  using Pair = double __attribute__((vector_size(16)));
  Lanes out;
  for (int h = 0; h < kPairLanes; h += 2) {
    const Pair root = _mm_sqrt_pd(Pair{v[h], v[h + 1]});
    out[h] = root[0];
    out[h + 1] = root[1];
  }
  return out;
#else
  Lanes out;
  for (int l = 0; l < kPairLanes; ++l) out[l] = __builtin_sqrt(v[l]);
  return out;
#endif
}
inline Lanes fabs(Lanes v) {
  return reinterpret_cast<Lanes>(reinterpret_cast<LaneMask>(v) & static_cast<std::int64_t>(0x7fffffffffffffffLL));
}
/// where ? a : b, lane by lane (`where` from a comparison: all bits set or clear).
inline Lanes select(LaneMask where, Lanes a, Lanes b) { return where ? a : b; }
inline LaneVec3 select(LaneMask where, const LaneVec3& a, const LaneVec3& b) {
  return {select(where, a.x, b.x), select(where, a.y, b.y), select(where, a.z, b.z)};
}
inline Lanes dot(const LaneVec3& a, const LaneVec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline LaneVec3 scaled(const LaneVec3& a, Lanes s) { return {a.x * s, a.y * s, a.z * s}; }
inline LaneVec3 minus(const LaneVec3& a, const LaneVec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline LaneVec3 plus(const LaneVec3& a, const LaneVec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline LaneVec3 cross(const LaneVec3& a, const LaneVec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace lanes

/// Whether hertz_pair_lanes computes `law`'s pair contacts (else the scalar loop does).
inline bool hertz_lanes_apply(const HertzMindlinLaw& law, const StepInputs& step) {
  const CoulombTangentialSpring& t = law.tangential;
  return step.laned_pair_law && step.rotation && law.cohesion.energy_density <= 0.0 && law.body_normal_compliance == 0.0 &&
         law.body_shear_compliance == 0.0 && (t.static_friction > 0.0 || t.dynamic_friction > 0.0) &&
         !(t.decay > 0.0 && t.static_friction != t.dynamic_friction);
}

/// Up to kPairLanes touching pairs (first < second, pair index into the history) and, after
/// hertz_pair_lanes, their loads.
struct PairLaneBatch {
  std::uint32_t first[kPairLanes]{};
  std::uint32_t second[kPairLanes]{};
  std::uint32_t pair[kPairLanes]{};
  int count = 0;
  PairLoads loads[kPairLanes]{};
};

namespace lanes {

inline LaneVec3 gather(const std::vector<Vec3>& v, const std::uint32_t* index) {
  LaneVec3 out;
  for (int l = 0; l < kPairLanes; ++l) {
    const Vec3& a = v[index[l]];
    out.x[l] = a.x;
    out.y[l] = a.y;
    out.z[l] = a.z;
  }
  return out;
}
inline Lanes gather(const std::vector<double>& v, const std::uint32_t* index) {
  Lanes out;
  for (int l = 0; l < kPairLanes; ++l) out[l] = v[index[l]];
  return out;
}

/// pair_geometry's quantities for the lanes (all lanes must overlap).
struct PairLaneGeometry {
  LaneVec3 normal, contact_velocity, relative_angular_velocity;
  Lanes overlap, branch_first, branch_second, effective_mass, effective_radius;
  Lanes normal_compliance, shear_compliance, inverse_inertia_sum;
};

inline PairLaneGeometry pair_lane_geometry(const ParticleState& p, const std::uint32_t* first,
                                           const std::uint32_t* second) {
  PairLaneGeometry g;
  const LaneVec3 d = minus(gather(p.position, second), gather(p.position, first));
  const Lanes radius_first = gather(p.radius, first), radius_second = gather(p.radius, second);
  const Lanes r_sum = radius_first + radius_second;
  const Lanes dist = sqrt(dot(d, d));
  g.normal = scaled(d, 1.0 / dist);
  g.overlap = r_sum - dist;
  g.branch_first = radius_first - 0.5 * g.overlap;
  g.branch_second = radius_second - 0.5 * g.overlap;
  const LaneVec3 spin_first = gather(p.angular_velocity, first), spin_second = gather(p.angular_velocity, second);
  g.contact_velocity = plus(minus(gather(p.velocity, first), gather(p.velocity, second)),
                            plus(cross(spin_first, scaled(g.normal, g.branch_first)),
                                 cross(spin_second, scaled(g.normal, g.branch_second))));
  g.relative_angular_velocity = minus(spin_first, spin_second);
  g.effective_mass = 1.0 / (gather(p.inverse_mass, first) + gather(p.inverse_mass, second));
  g.effective_radius = radius_first * radius_second / r_sum;
  g.normal_compliance = gather(p.normal_compliance, first) + gather(p.normal_compliance, second);
  g.shear_compliance = gather(p.shear_compliance, first) + gather(p.shear_compliance, second);
  g.inverse_inertia_sum = gather(p.inverse_inertia, first) + gather(p.inverse_inertia, second);
  return g;
}

/// CoulombTangentialSpring::evaluate with mu = FRICS; `xi` is the stored elongation, updated.
inline LaneVec3 tangential_lanes(const PairLaneGeometry& g, Lanes stiffness, Lanes damping, Lanes normal_force,
                                 double friction, LaneVec3& xi, double dt) {
  const LaneVec3& n = g.normal;
  const LaneVec3 v_t = minus(g.contact_velocity, scaled(n, dot(g.contact_velocity, n)));
  const Lanes old_length2 = dot(xi, xi);
  const LaneVec3 turned = minus(xi, scaled(n, dot(xi, n)));
  const Lanes new_length2 = dot(turned, turned);
  const LaneVec3 kept = select(new_length2 > 0.0, scaled(turned, sqrt(old_length2 / new_length2)), turned);
  xi = plus(select(old_length2 > 0.0, kept, xi), scaled(v_t, splat(dt)));
  LaneVec3 f_t = minus(scaled(xi, -stiffness), scaled(v_t, damping));
  const Lanes limit = friction * fabs(normal_force);
  const Lanes f_t_length2 = dot(f_t, f_t);
  const LaneMask sliding = f_t_length2 > limit * limit;
  const LaneVec3 limited = scaled(f_t, limit / sqrt(f_t_length2));
  const LaneVec3 spring = select(stiffness > 0.0, scaled(plus(limited, scaled(v_t, damping)), -1.0 / stiffness),
                                 LaneVec3{Lanes{}, Lanes{}, Lanes{}});
  xi = select(sliding, spring, xi);
  return select(sliding, limited, f_t);
}

/// ConstantTorqueRolling::evaluate.
inline LaneVec3 rolling_lanes(const PairLaneGeometry& g, double coefficient, Lanes normal_force, double dt) {
  const LaneVec3 zero{Lanes{}, Lanes{}, Lanes{}};
  if (coefficient <= 0.0) return zero;
  const LaneVec3& w = g.relative_angular_velocity;
  const Lanes w_length = sqrt(dot(w, w));
  Lanes magnitude = coefficient * fabs(normal_force) * g.effective_radius;
  const Lanes stopping = w_length / (dt * g.inverse_inertia_sum);
  magnitude = select(magnitude > stopping, stopping, magnitude);
  return select(w_length <= 0.0, zero, scaled(w, -magnitude / w_length));
}

}  // namespace lanes

/// Loads of the batch's pairs (HertzMindlinLaw::force and pair_loads' torques, lane by lane) and
/// their tangential springs advanced by dt; lanes past `count` repeat lane 0's pair and are
/// discarded. Requires hertz_lanes_apply(law, step) and every pair overlapping.
inline void hertz_pair_lanes(const HertzMindlinLaw& law, ContactHistory* history, const ParticleState& p,
                             const StepInputs& step, PairLaneBatch& b) {
  using namespace lanes;
  for (int l = b.count; l < kPairLanes; ++l) {
    b.first[l] = b.first[0];
    b.second[l] = b.second[0];
  }
  const PairLaneGeometry g = pair_lane_geometry(p, b.first, b.second);
  // HertzNormal::evaluate
  const Lanes e_star = 1.0 / g.normal_compliance;
  const Lanes a = sqrt(g.effective_radius * g.overlap);
  const Lanes elastic = (4.0 / 3.0) * e_star * a * g.overlap;
  const Lanes s_n = 2.0 * e_star * a;
  const double damping_factor = -2.0 * std::sqrt(5.0 / 6.0) * law.normal.beta;
  const Lanes c_n = damping_factor * sqrt(s_n * g.effective_mass);
  const Lanes normal_force = elastic + c_n * dot(g.contact_velocity, g.normal);
  // HertzLaw::force
  const Lanes s_t = 8.0 * a / g.shear_compliance;
  const Lanes c_t = damping_factor * sqrt(s_t * g.effective_mass);
  LaneVec3 xi;
  for (int l = 0; l < kPairLanes; ++l) {
    const Vec3& stored = history[l < b.count ? b.pair[l] : b.pair[0]].tangential_displacement;
    xi.x[l] = stored.x;
    xi.y[l] = stored.y;
    xi.z[l] = stored.z;
  }
  const LaneVec3 f_t = tangential_lanes(g, s_t, c_t, normal_force, law.tangential.static_friction, xi, step.dt);
  const LaneVec3 force = minus(f_t, scaled(g.normal, normal_force));
  const LaneVec3 rolling = rolling_lanes(g, law.rolling.coefficient, normal_force, step.dt);
  const LaneVec3 torque_first = plus(cross(scaled(g.normal, g.branch_first), f_t), rolling);
  const LaneVec3 torque_second = minus(cross(scaled(g.normal, g.branch_second), f_t), rolling);
  for (int l = 0; l < b.count; ++l) {
    history[b.pair[l]].tangential_displacement = {xi.x[l], xi.y[l], xi.z[l]};
    b.loads[l] = {{force.x[l], force.y[l], force.z[l]},
                  {torque_first.x[l], torque_first.y[l], torque_first.z[l]},
                  {torque_second.x[l], torque_second.y[l], torque_second.z[l]}};
  }
}

}  // namespace demfit::dem_core
