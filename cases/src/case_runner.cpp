// Dispatch of a case to its adapter (see case_runner.hpp).
#include "demfit/cases/case_runner.hpp"

#include <cstdlib>

#include "dem_setup.hpp"
#include "drum_case.hpp"
#include "pellet_case.hpp"

namespace demfit::cases {

std::filesystem::path default_cache_dir() {
  if (const char* dir = std::getenv("DEMFIT_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "demfit";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "demfit";
  return ".demfit-cache";
}

CaseResult run_case(const CaseSpec& spec, const identify::ParameterSet& parameters,
                    const CaseRunOptions& options) {
  CaseRunOptions resolved = options;
  if (resolved.cache_dir.empty()) resolved.cache_dir = default_cache_dir();
  const CaseSpec evaluated = detail::with_parameters(spec, parameters);
  if (spec.kind == CaseKind::pellet_compression) {
    return detail::run_pellet_compression(spec, evaluated, resolved);
  }
  return detail::run_rotary_drum(spec, evaluated, resolved);
}

}  // namespace demfit::cases
