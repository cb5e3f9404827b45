#pragma once
// Internal: CaseSpec pieces -> dem_core inputs, and the evaluated-parameter overrides.
#include <initializer_list>
#include <string>

#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/fill_cache.hpp"
#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "demfit/identify/model.hpp"

namespace demfit::cases::detail {

// Time-step factor of fill generation (pouring, settling, densification): fixed, so a fill does
// not depend on the case's time_step.factor (which is not part of the fill cache key). dem_core's
// automatic step also applies its packing/damping bounds (dem_core/time_step.hpp).
inline constexpr double kFillTimeStepFactor = 0.15;

dem_core::Material to_material(const MaterialSpec& spec);

/// The fill cache key of a case: everything the settled fill depends on (to_key_json, so effects
/// at their off values and insertion order leave it as before them), with the kind's `section`
/// minus its `run_only` keys (the measured stage's settings, which do not change the fill).
nlohmann::json fill_key_of(const CaseSpec& spec, const char* section, std::initializer_list<const char*> run_only);

/// Law, particle contact parameters and particle order of the spec; callers set gravity, threads
/// and steps.
dem_core::SimulationSettings simulation_settings(const CaseSpec& spec);

// The particles of a settled simulation as a cacheable fill (positions [m], radii [m]).
Fill fill_of(const dem_core::Simulation& simulation);

// Copies `base` with the identified parameters in `parameters` applied (rows of the parameter
// table). A value equal to the case's own is no change; otherwise an unknown name, a parameter of
// the other contact law or of a drum in a pellet case, or a value outside the row's valid range
// is an error naming the parameter.
CaseSpec with_parameters(const CaseSpec& base, const identify::ParameterSet& parameters);

// The identified-parameter values of a spec, by name: the parameters of its contact law, and the
// drum fill amount when the case gives it as particle_count or fill_volume_ml.
identify::ParameterSet parameters_of(const CaseSpec& spec);

// Throws "'time_step.value' = ... exceeds the stable limit ..." when the user step is too large
// for the simulation's current particles and walls.
void check_user_time_step(const CaseSpec& spec, const dem_core::Simulation& simulation);

// The same check before any expensive work: a probe simulation with one particle of the
// smallest radius of the spec's spread around the nominal `radius` [m], density [kg/m^3], and
// one wall with the spec's wall parameters (the stable step depends on particle size, material
// and contact parameters, not on positions).
void precheck_user_time_step(const CaseSpec& spec, double radius, double density);

// The time step [s] a run of `spec` would use for particles of radius `radius` [m] and density
// [kg/m^3]: the user's step, or the automatic one of the same probe.
double planned_time_step(const CaseSpec& spec, double radius, double density);

// Writes VTK snapshots of `simulation` named <dir>/<stage>_<time>.vtk for every time in
// `times` that the stage crossed since the last call (times measured from the stage start).
class SnapshotSchedule {
 public:
  SnapshotSchedule(std::vector<double> times, std::string directory, std::string stage);
  void maybe_write(const dem_core::Simulation& simulation, double stage_time);

 private:
  std::vector<double> times_;
  std::string directory_;
  std::string stage_;
  std::size_t next_ = 0;
};

}  // namespace demfit::cases::detail
