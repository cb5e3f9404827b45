#pragma once
// Particle–wall contact slots (internal state of Simulation): for each particle, only the walls it
// may touch before the next neighbour-list rebuild (within R + skin at the build, or every wall
// whose motion changes distances), in CSR form with walls ascending, and the last loads of each
// slot (the slots' contact histories, of the law's history type, are kept with the law's state:
// contact_laws.hpp). A dense (particle x wall) layout cost ~106 bytes per particle per wall
// although most particles touch no wall. A mesh wall's slots of a particle also list the
// triangles within R + skin at the build (CSR over slots, all on the group's first slot): the
// contact test then reads those few triangles instead of the mesh's cells on every step.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

struct WallSlots {
  std::vector<std::uint32_t> rows{};  ///< slots of particle i: [rows[i], rows[i+1]); empty = not built
  std::vector<std::uint32_t> wall{};  ///< wall index of each slot
  std::vector<Vec3> force_on_particle{}, contact_point{}, rolling_torque{};  ///< last evaluation
  std::vector<double> energy{};
  std::vector<std::uint8_t> touching{};
  /// Candidate triangles of slot k: triangles[triangle_rows[k] .. triangle_rows[k+1]); both empty
  /// when no wall is a mesh.
  std::vector<std::uint32_t> triangle_rows{}, triangles{};

  [[nodiscard]] std::size_t size() const { return wall.size(); }
  [[nodiscard]] bool built_for(std::size_t particles) const { return rows.size() == particles + 1; }
  /// Drops every slot (walls added, particles removed).
  void clear() { *this = WallSlots{}; }
};

}  // namespace demfit::dem_core
