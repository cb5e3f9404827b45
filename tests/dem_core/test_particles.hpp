#pragma once
// The particles, material and gravity that several dem_core tests share, and their bitwise
// comparison of states. One definition here rather than a file-local copy in each test: the test
// files of test_dem_core are compiled together as unity batches (DEMFIT_UNITY_BUILD), where two
// copies of one name would collide.
#include <cstring>
#include <numbers>
#include <vector>

#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core::test {

/// Standard gravity [m/s^2].
inline constexpr double kGravity = 9.81;

/// The linear-law tests' material: bulk modulus K = 1 GPa, density 2500 kg/m^3, Poisson ratio 0.3.
inline const Material kTestMaterial{1.0e9, 2500.0, 0.3};
/// The linear-law tests' sphere radius [m].
inline constexpr double kSphereRadius = 1.0e-3;

/// Mass of a sphere of radius r [m] of kTestMaterial [kg].
inline double sphere_mass(double r) { return kTestMaterial.density * 4.0 / 3.0 * std::numbers::pi * r * r * r; }

/// The Hertz–Mindlin tests' soft material: Young's modulus E = 10 MPa, Poisson ratio 0.3, density
/// 2500 kg/m^3; as a Material, with the bulk modulus K = E / (3 (1 - 2 nu)).
inline constexpr double kHertzYoung = 1.0e7;  // E [Pa]
inline constexpr double kHertzPoisson = 0.3;
inline constexpr double kHertzDensity = 2500.0;  // [kg/m^3]
inline const Material kHertzMaterial{kHertzYoung / (3.0 * (1.0 - 2.0 * kHertzPoisson)), kHertzDensity, kHertzPoisson};

/// Whether two states are identical bit for bit (determinism: equal, not close).
inline bool bitwise_equal(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

}  // namespace demfit::dem_core::test
