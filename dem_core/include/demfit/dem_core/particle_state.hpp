#pragma once
// Particle state as a structure of arrays: one contiguous array per quantity, indexed by the
// particle index (the layout of the hot loops). Solid spheres: m = rho 4/3 pi R^3, I = 2/5 m R^2.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

struct ParticleState {
  // kinematics (global frame)
  std::vector<Vec3> position{};          ///< centre [m]
  std::vector<Vec3> velocity{};          ///< [m/s]
  std::vector<Vec3> angular_velocity{};  ///< [rad/s]
  // resultant loads of the last force evaluation (contacts + gravity)
  std::vector<Vec3> force{};   ///< [N]
  std::vector<Vec3> torque{};  ///< [N·m] about the particle centre
  // constant properties
  std::vector<double> radius{};           ///< [m]
  std::vector<double> mass{};             ///< [kg]
  std::vector<double> inverse_mass{};     ///< [1/kg]
  std::vector<double> inverse_inertia{};  ///< 1/I [1/(kg m^2)], I = 2/5 m R^2
  std::vector<std::size_t> material{};    ///< index into Simulation's material table
  /// Identity: the n-th particle ever added has id n. Equal to the index unless particles were
  /// removed or SimulationSettings::reorder_particles moved them.
  std::vector<std::uint32_t> id{};
  /// Normal compliance of the particle's own "half" of a contact, set by the law's
  /// `particle_compliance` (contact_laws.hpp); a pair's stiffness is the inverse of the sum of
  /// both compliances (springs in series). Linear law: 1/(NORMK K R) [m/N]; Hertz: (1-nu^2)/E [1/Pa].
  std::vector<double> normal_compliance{};
  /// Hertz–Mindlin only: (2-nu)/G [1/Pa] (series sum gives 1/G*). Unused by the linear law.
  std::vector<double> shear_compliance{};

  [[nodiscard]] std::size_t size() const { return position.size(); }

  /// Calls `f(array)` for every per-particle array: the one list that removal, reordering and
  /// any other whole-state operation use, so a new array cannot be forgotten by one of them.
  template <class F>
  void for_each_array(F&& f) {
    f(position), f(velocity), f(angular_velocity), f(force), f(torque);
    f(radius), f(mass), f(inverse_mass), f(inverse_inertia), f(material), f(id);
    f(normal_compliance), f(shear_compliance);
  }

  /// Particle indices in ascending id: the order of every output (snapshots, particle tables),
  /// so that files do not depend on where SimulationSettings::reorder_particles put particles.
  [[nodiscard]] std::vector<std::size_t> indices_by_id() const {
    std::vector<std::size_t> order(id.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
    return order;
  }
};

}  // namespace demfit::dem_core
