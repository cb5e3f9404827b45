#pragma once
// demfit vs LIGGGHTS on the same problem: N spheres (R = 1 mm, rho = 2500 kg/m^3) on a simple
// cubic lattice settling in a box under gravity, Hertz–Mindlin on both sides, same time step.
#include <string>

namespace demfit::bench {

struct LiggghtsComparison {
  bool ran = false;
  std::string note;              ///< why it was skipped, or the executable used
  long particles = 0;            ///< demfit particle count (LIGGGHTS creates the same lattice)
  long liggghts_particles = 0;   ///< "Created N atoms" from the LIGGGHTS log
  long steps = 0;
  double time_step = 0.0;        ///< [s]
  double demfit_seconds = 0.0;   ///< CPU seconds for `steps` steps (1 thread)
  double liggghts_seconds = 0.0; ///< LIGGGHTS "Loop time" (wall clock of its time loop)
  double liggghts_cpu_seconds = 0.0;  ///< CPU seconds of the whole LIGGGHTS process (incl. setup)
  double demfit_kinetic_energy = 0.0;    ///< [J] at the end (translational + rotational)
  double liggghts_kinetic_energy = 0.0;  ///< [J] last thermo KinEng (translational only)
};

LiggghtsComparison compare_with_liggghts(long steps);

}  // namespace demfit::bench
