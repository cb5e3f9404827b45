#pragma once
// The same drum for LIGGGHTS 3.8: demfit's settled, flowing bed as a `read_data` file (atom_style
// granular, with velocities and angular velocities), the drum as an ASCII STL triangle mesh
// (shell + both end caps, turned with `fix move/mesh rotate`), and an input script with output
// off except the thermo line of the first and last step. Runs it and parses its loop time.
#include <filesystem>
#include <string>

#include "demfit/dem_core/simulation.hpp"
#include "hertz_drum.hpp"

namespace demfit::bench {

/// Triangles of the drum mesh: `segments` around (shell split into `shell_rings` axial rings),
/// end caps as concentric rings. Written by write_liggghts_drum.
struct DrumMeshShape {
  int segments = 360;  ///< facets within ~1 um of the 50 mm cylinder
  int shell_rings = 1;
  int cap_rings = 2;  ///< 2160 triangles in all (LIGGGHTS' cost grows with the count: printed)
};

/// Writes bed.data, drum.stl and in.drum into `dir` (created). `sim` is the demfit state both
/// codes start from; its shell's accumulated rotation angle is applied to the mesh.
/// Returns the number of mesh triangles.
std::size_t write_liggghts_drum(const std::filesystem::path& dir, const HertzDrumSpec& spec,
                                const dem_core::Simulation& sim, long steps, const DrumMeshShape& mesh = {});

struct LiggghtsRun {
  bool ok = false;
  std::string note;           ///< failure reason (and where the log is)
  double loop_seconds = 0.0;  ///< "Loop time of T on P procs for N steps with M atoms"
  long procs = 0, steps = 0, atoms = 0;
  long neighbour_builds = 0;                                               ///< "Neighbor list builds = "
  double pair_seconds = 0.0, neighbour_seconds = 0.0, comm_seconds = 0.0;  ///< its timing breakdown
  double kinetic_energy = 0.0;                                             ///< last thermo `ke` (translational) [J]
  double centre_x = 0.0, centre_y = 0.0;                                   ///< last thermo centre of mass [m]
  [[nodiscard]] double particle_steps_per_second() const {
    return loop_seconds > 0.0 ? static_cast<double>(atoms) * static_cast<double>(steps) / loop_seconds : 0.0;
  }
  /// The rate if only its pair, neighbour and communication time counted (walls and integration
  /// free): an upper bound on LIGGGHTS without its mesh.
  [[nodiscard]] double particle_steps_per_second_without_fixes() const {
    const double t = pair_seconds + neighbour_seconds + comm_seconds;
    return t > 0.0 ? static_cast<double>(atoms) * static_cast<double>(steps) / t : 0.0;
  }
};

/// Runs `liggghts -in in.drum` in `dir` (1 rank), or `mpirun -np P liggghts -var px .. -var py ..
/// -var pz ..` when the split (px, py, pz) has more than one rank. `out_name` receives its output.
LiggghtsRun run_liggghts_drum(const std::filesystem::path& dir, int px, int py, int pz, const std::string& out_name);

/// "liggghts" when it is on PATH, else empty.
std::string liggghts_executable();

}  // namespace demfit::bench
