#pragma once
// A case file, typed (SPEC 2, SPEC 4). Parsing is strict: unknown keys, wrong types and
// impossible values are errors naming the dotted field. Every quantity is SI (m, kg, s, Pa)
// unless the key names its unit (e.g. "rpm"). to_json() gives the resolved case with every
// default filled in; parse_case(to_json(spec)) == spec.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/coarse_graining.hpp"
#include "demfit/dem_core/parameters.hpp"

namespace demfit::cases {

// Particle material (one species per case). The particle spring is NORMK * K * R with
// K = E / (3 (1 - 2 nu)) (paper section 2, SPEC 1).
struct MaterialSpec {
  double radius = 1.0e-3;          // [m]
  double density = 1000.0;         // [kg/m^3]
  double youngs_modulus = 1.0e9;   // E [Pa]
  double poisson_ratio = 0.3;      // nu [-], < 0.5
  // Polydispersity (effects library): relative radius spread s, radii uniform in
  // [R(1 - s), R(1 + s)] at the same solid volume (dem_core PackingRequest::radius_spread);
  // 0 = monodisperse (off). Changes the fill, so it is part of the fill cache key when > 0.
  double radius_spread = 0.0;      // [-], in [0, 0.3]
  double bulk_modulus() const;     // K [Pa]
};

// *CONTROL_DISCRETE_ELEMENT (particle pairs, with the effects library) and
// *DEFINE_DE_TO_SURFACE_COUPLING card 2 (walls: fricd is the wall ROLLING friction), LS-DYNA
// semantics (SPEC 1): the case holds dem_core's own parameter sets. Parsing resolves FRICD to
// FRICS when the file omits it, so a parsed case never carries dem_core's "unset" (-1).
using ContactSpec = dem_core::ContactParameters;
using WallContactSpec = dem_core::WallContactParameters;

struct TimeStepSpec {
  double value = 0.0;    // user time step [s]; 0 = automatic
  double factor = 0.15;  // automatic step = factor * 2 pi sqrt(m*/k_n) of the stiffest pair
};

// SPEC 2.1. The cylinder axis is z, the bottom plate at z = 0.
struct PelletSpec {
  double container_diameter = 0.036;  // [m]
  double container_height = 0.064;    // [m]
  long long particle_count = 1450;
  long long fill_seed = 1;            // seed of the random pouring positions
  double fill_normk = 0.01;           // NORMK used while pouring/settling the fill (cached)
  double settle_time = 0.6;           // simulated pouring + settling time [s]
  double piston_speed = 0.05;         // [m/s], downward
  double max_pressure = 3.0e6;        // piston pressure that ends loading [Pa]
  double max_travel = 0.03;           // safety stop of the piston stroke [m]
  bool unload = false;                // also unload to zero force at the same speed
  long long curve_points = 60;        // resampled points of pressure_volume (loading part)
};

// SPEC 2.2. Drum axis z through the origin, gravity -y.
struct DrumSpec {
  double diameter = 0.1;               // inner diameter [m]
  double length = 0.025;               // axial length between the end walls [m]
  double rpm = 60.0;                   // rotation speed [rev/min]
  double duration = 3.0;               // simulated rotation time [s]
  double fill_fraction = 0.3;          // bulk fill as a fraction of the drum volume
  double volume_fraction = 0.64;       // phi of the packed fill and of Table 2
  CoarseGraining coarse_graining = CoarseGraining::scg;
  double scale_factor = 1.0;           // s of Table 2 (1 = original particles)
  long long fill_seed = 1;
  double densify_time = 0.4;           // settling before rotation starts [s]
  double torque_interval = 0.01;       // sampling interval of the torque history [s]
  double surface_window = 0.1;         // free surface averaged over [duration - window, duration] [s]
  long long surface_snapshots = 5;     // snapshots averaged in that window
  long long surface_points = 41;       // abscissae of the free_surface curve
};

struct OutputSpec {
  std::vector<double> snapshot_times;  // [s] VTK snapshots of the particles (empty = none)
  double progress_interval = 1.0;      // wall-clock seconds between progress updates
};

enum class CaseKind { pellet_compression, rotary_drum };

struct CaseSpec {
  CaseKind kind = CaseKind::pellet_compression;
  std::string description;
  MaterialSpec material;
  ContactSpec contact;
  WallContactSpec wall;
  TimeStepSpec time_step;
  OutputSpec output;
  PelletSpec pellet;  // used when kind == pellet_compression
  DrumSpec drum;      // used when kind == rotary_drum
};

CaseSpec parse_case(const nlohmann::json& document);
nlohmann::json to_json(const CaseSpec& spec);

// to_json without the effects-library fields that are at their off values
// (particle.radius_spread = 0, contact.unloading_stiffness_ratio = 1, contact.surface_energy = 0,
// contact.stiffness_exponent = 1): the text of a case without effects is the text it had before
// the effects existed, so cache keys built from it (fills, results) stay valid.
nlohmann::json to_key_json(const CaseSpec& spec);

// Reads a case file; a missing file or malformed JSON is an error naming the file.
nlohmann::json read_case_json(const std::string& path);

// Applies "name=value" overrides to a case document before parsing. `name` is an identified
// parameter (normk sheark ndamp tdamp frics fricd dc fricr wall_frics wall_fricd wall_damp
// wall_sfp, and the effects unloading_stiffness_ratio surface_energy stiffness_exponent
// radius_spread) or a dotted path ("pellet.piston_speed"); `value` is JSON (a number, true/false or a
// quoted string; a bare word is taken as a string).
void apply_setting(nlohmann::json& document, const std::string& assignment);

// Dotted JSON path of an identified parameter name ("normk" -> "contact.normk",
// "wall_damp" -> "wall_contact.damp", "radius_spread" -> "particle.radius_spread");
// empty when the name is not a parameter.
std::string parameter_path(const std::string& name);

// The identified-parameter names, in a fixed order.
const std::vector<std::string>& parameter_names();

}  // namespace demfit::cases
