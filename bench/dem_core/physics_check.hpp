#pragma once
// Physics cross-check of the Hertz–Mindlin options against LIGGGHTS 3.8 on the Hertz drum
// (hertz_drum.hpp): ONE bed settled and spun up by demfit, then continued from that state in
// both codes for the same time with each contact-law variant:
//   cdt   - constant-torque rolling friction 0.1, no cohesion (the control: the anchor's law);
//   sjkr  - as cdt plus SJKR cohesion (`cohesion sjkr`, pairs and walls) at k_c [J/m^3];
//   epsd2 - elastic-plastic spring rolling friction 0.1 (`rolling_friction epsd2`), no cohesion.
// demfit runs with its analytic walls (cylinder and two disks), LIGGGHTS with the STL drum; both
// start without contact histories. Compared per variant: the mean drive torque over the second
// half of the run (LIGGGHTS: minus the moment of the particles' forces on the mesh; demfit: minus
// the walls' torque about the axis, which also counts the rolling couples), the bed's gravity
// moment M g x_c over the same windows, and the mid-depth slab angle (cases/bed_angles.hpp, the
// same function on both codes' positions) averaged over the snapshots of the second half.
#include <filesystem>
#include <string>
#include <vector>

#include "liggghts_drum.hpp"

namespace demfit::bench {

struct PhysicsCheckOptions {
  double settle_time = 0.3;   ///< [s] drum at rest (demfit)
  double spin_up_time = 0.5;  ///< [s] turning with cdt before the restart (demfit)
  double run_time = 0.5;      ///< [s] of each variant after the restart, both codes
  double window = 0.05;       ///< [s] averaging window of the torque and snapshots
  /// k_c of the sjkr variant [J/m^3]: raises the slab angle ~7 deg over cdt; 60e3 consolidates the
  /// bed into a block that slips on the shell (in both codes).
  double cohesion_energy_density = 35e3;
  std::vector<std::string> variants{"cdt", "sjkr", "epsd2"};
  std::filesystem::path dir;  ///< LIGGGHTS files
  DrumMeshShape mesh{};       ///< LIGGGHTS' drum mesh
};

void check_physics_against_liggghts(const PhysicsCheckOptions& options);

}  // namespace demfit::bench
