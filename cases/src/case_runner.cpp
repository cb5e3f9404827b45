// Dispatch of a case to its adapter (see case_runner.hpp).
#include "demfit/cases/case_runner.hpp"

#include <cstdlib>
#include <stdexcept>

#include "dem_setup.hpp"
#include "drum_case.hpp"
#include "mesh_container_case.hpp"
#include "pellet_case.hpp"

namespace demfit::cases {

std::filesystem::path default_cache_dir() {
  if (const char* dir = std::getenv("DEMFIT_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "demfit";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "demfit";
  return ".demfit-cache";
}

CaseResult run_case(const CaseSpec& spec, const identify::ParameterSet& parameters, const CaseRunOptions& options) {
  CaseRunOptions resolved = options;
  if (resolved.cache_dir.empty()) resolved.cache_dir = default_cache_dir();
  const CaseSpec evaluated = detail::with_parameters(spec, parameters);
  // The fill is made with the case's contact values (they are not evaluated parameters of the
  // fill), but radius_spread changes the particles themselves, so it is taken from the
  // evaluated spec (one cached fill per distinct spread).
  CaseSpec fill = spec;
  fill.material.radius_spread = evaluated.material.radius_spread;
  // Likewise the drum fill amount (particle_count, fill_volume_ml): one cached fill per value.
  fill.drum.fill_by = evaluated.drum.fill_by;
  fill.drum.particle_count = evaluated.drum.particle_count;
  fill.drum.fill_volume_ml = evaluated.drum.fill_volume_ml;
  switch (spec.kind) {  // exhaustive (case_registry.hpp)
    case CaseKind::pellet_compression:
      return detail::run_pellet_compression(fill, evaluated, resolved);
    case CaseKind::rotary_drum:
      return detail::run_rotary_drum(fill, evaluated, resolved);
    case CaseKind::mesh_container:  // no cached fill: the pour is the measured stage
      return detail::run_mesh_container(evaluated, resolved);
  }
  throw std::logic_error("run_case: a CaseKind without a runner");
}

}  // namespace demfit::cases
