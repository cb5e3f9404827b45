#pragma once
// LIGGGHTS 3.8 side of the physics cross-check (physics_check.hpp): an input script that
// continues the bed of bed.data (written by write_liggghts_drum) in the rotating STL drum with
// one contact-law variant, and the figures read back from its log and its dump.
//
// Figures, every `window_steps` steps:
//   - drive torque about +z: minus the moment of the particles' forces on the mesh about the
//     axis (fix mesh/surface/stress, global vector element 6), averaged by fix ave/time over
//     every 10th step of the window;
//   - centre of mass x of the bed (compute com), averaged the same way;
//   - positions and radii (dump custom id x y z radius) at the end of each window.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "demfit/dem_core/parameters.hpp"
#include "hertz_drum.hpp"

namespace demfit::bench {

/// One contact-law variant of the check, as both codes name it.
struct LawVariant {
  std::string name;                    ///< "cdt", "sjkr", "epsd2" (file names)
  double cohesion_energy_density = 0;  ///< k_c [J/m^3]; 0 = no cohesion model
  dem_core::CohesionModel cohesion = dem_core::CohesionModel::sjkr;
  dem_core::RollingModel rolling = dem_core::RollingModel::constant_torque;
};

/// The LIGGGHTS `model ...` words of the variant: "hertz tangential history [cohesion sjkr]
/// rolling_friction cdt|epsd2".
std::string liggghts_model_words(const LawVariant& variant);

/// Writes in.<variant> into `dir` (bed.data and drum.stl must be there already).
void write_physics_input(const std::filesystem::path& dir, const HertzDrumSpec& spec, const LawVariant& variant,
                         long steps, long window_steps);

/// One window's figures (both codes fill the same record).
struct WindowFigures {
  double time = 0.0;          ///< end of the window since the restart [s]
  double drive_torque = 0.0;  ///< [N m], mean over the window
  double centre_x = 0.0;      ///< [m], mean over the window
};

/// A bed snapshot: positions [m] and radii [m].
struct BedSnapshot {
  double time = 0.0;  ///< since the restart [s]
  std::vector<std::array<double, 3>> positions;
  std::vector<double> radii;
};

struct PhysicsRun {
  bool ok = false;
  std::string note;  ///< failure reason
  double wall_seconds = 0.0;
  std::vector<WindowFigures> windows;
  std::vector<BedSnapshot> snapshots;
};

/// Runs `liggghts -in in.<variant>` in `dir` (1 rank) and reads its windows and snapshots.
PhysicsRun run_liggghts_physics(const std::filesystem::path& dir, const LawVariant& variant, double time_step);

}  // namespace demfit::bench
