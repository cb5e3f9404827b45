#pragma once
// Internal: the drum's powder (the fill amount rule and Table 2 coarse graining applied to it)
// and its packed, densified fill, shared by the fill and the rotation stages of the drum case.
#include <vector>

#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/coarse_graining.hpp"
#include "demfit/cases/fill_cache.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "nlohmann/json.hpp"

namespace demfit::cases::detail {

struct Powder {
  CoarseParticle particle;  // monodisperse: the particle; distribution: its smallest one
  long long count = 0;
  double original_total_mass = 0.0;  // M0 [kg]
  double original_count = 0.0;       // N0 (real: the rule's value before rounding)
  double bulk_fraction = 0.0;        // original bulk volume / drum volume (packing start)
  std::vector<double> radii;         // size distribution: the coarse radii [m]; empty = monodisperse
};

// The powder a drum case simulates (count, coarse particle, sampled radii).
Powder powder_of(const CaseSpec& spec);
// The coarse particles' material (density of the coarse model, Table 2).
dem_core::Material powder_material(const CaseSpec& spec, const Powder& powder);
// Drum shell and end walls, all rotating about the z axis at `omega` [rad/s]; returns the first
// wall index (three walls: shell, end at z = 0, end at z = length).
std::size_t add_drum(dem_core::Simulation& sim, const CaseSpec& spec, double omega);
// What the cached fill depends on (the rotation settings do not enter it).
nlohmann::json fill_key(const CaseSpec& spec);
// Packed generation in the lower part of the drum, then densification (the fill stage).
Fill pack_and_densify(const CaseSpec& spec, const CaseRunOptions& options);

}  // namespace demfit::cases::detail
