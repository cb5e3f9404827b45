#pragma once
// A case file, typed (docs/spec.md 2, docs/spec.md 4). Parsing is strict: unknown keys, wrong types and
// impossible values are errors naming the dotted field. Every quantity is SI (m, kg, s, Pa)
// unless the key names its unit (e.g. "rpm"). to_json() gives the resolved case with every
// default filled in; parse_case(to_json(spec)) == spec.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/coarse_graining.hpp"
#include "demfit/cases/drum_wall_mesh.hpp"
#include "demfit/cases/size_distribution.hpp"
#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "demfit/dem_core/stl_mesh.hpp"

namespace demfit::cases {

// Particle material (one species per case). The particle spring is NORMK * K * R with
// K = E / (3 (1 - 2 nu)) (paper section 2, docs/spec.md 1).
struct MaterialSpec {
  double radius = 1.0e-3;         // [m]
  double density = 1000.0;        // [kg/m^3]
  double youngs_modulus = 1.0e9;  // E [Pa]
  double poisson_ratio = 0.3;     // nu [-], < 0.5
  // Polydispersity (effects library): relative radius spread s, radii uniform in
  // [R(1 - s), R(1 + s)] at the same solid volume (dem_core PackingRequest::radius_spread);
  // 0 = monodisperse (off). Changes the fill, so it is part of the fill cache key when > 0.
  double radius_spread = 0.0;   // [-], in [0, 0.3]
  double bulk_modulus() const;  // K [Pa]
};

// *CONTROL_DISCRETE_ELEMENT (particle pairs, with the effects library) and
// *DEFINE_DE_TO_SURFACE_COUPLING card 2 (walls: fricd is the wall ROLLING friction), LS-DYNA
// semantics (docs/spec.md 1): the case holds dem_core's own parameter sets. Parsing resolves FRICD to
// FRICS when the file omits it, so a parsed case never carries dem_core's "unset" (-1).
using ContactSpec = dem_core::ContactParameters;
using WallContactSpec = dem_core::WallContactParameters;

struct TimeStepSpec {
  double value = 0.0;    // user time step [s]; 0 = automatic
  double factor = 0.15;  // automatic step = factor * 2 pi sqrt(m*/k_n) of the stiffest pair
};

// docs/spec.md 2.1. The cylinder axis is z, the bottom plate at z = 0.
struct PelletSpec {
  double container_diameter = 0.036;  // [m]
  double container_height = 0.064;    // [m]
  long long particle_count = 1450;
  long long fill_seed = 1;      // seed of the random pouring positions
  double fill_normk = 0.01;     // NORMK used while pouring/settling the fill (cached)
  double settle_time = 0.6;     // simulated pouring + settling time [s]
  double piston_speed = 0.05;   // [m/s], downward
  double max_pressure = 3.0e6;  // piston pressure that ends loading [Pa]
  double max_travel = 0.03;     // safety stop of the piston stroke [m]
  bool unload = false;          // also unload to zero force at the same speed
  long long curve_points = 60;  // resampled points of pressure_volume (loading part)
};

// How the drum fill amount is given (exactly one per case file; fill_fraction when none is).
//   fill_fraction f: bulk volume f * drum volume;  fill_volume_ml V: bulk volume V [mL];
//   the original (s = 1) particles' solid volume is volume_fraction * bulk volume, so their count
//   is N0 = phi V_bulk / E[v] (E[v] = mean sphere volume of the size distribution);
//   particle_count N0: original particles directly;  fill_mass M: N0 = M / (rho E[v]).
// The coarse model carries Table 2's total mass: SCG count = N0 / s^3, CVF count = phi N0 / s^3.
enum class FillBy { fill_fraction, fill_volume, particle_count, fill_mass };

// The simulated side of a photo comparison: occupancy image of the particles
// projected along the drum axis, averaged over the surface window, then the photo's surface
// extraction (demfit::imaging). Off unless "image" is given in the drum object.
struct DrumImageSpec {
  bool enabled = false;
  long long pixels = 406;  // image width = height, spanning the inner diameter (GranuDrum: 406)
  double margin = 0.1;     // compared circle (1 - margin) R, as for the photo
  long long points = 41;   // abscissae of free_surface_image
};

// docs/spec.md 2.2. Drum axis z through the origin, gravity -y.
struct DrumSpec {
  double diameter = 0.1;          // inner diameter [m]
  double length = 0.025;          // axial length between the end walls [m]
  double rpm = 60.0;              // rotation speed [rev/min]
  double duration = 3.0;          // simulated rotation time [s]
  double fill_fraction = 0.3;     // bulk fill as a fraction of the drum volume
  double volume_fraction = 0.64;  // phi of the packed fill and of Table 2
  CoarseGraining coarse_graining = CoarseGraining::scg;
  double scale_factor = 1.0;  // s of Table 2 (1 = original particles)
  long long fill_seed = 1;
  double densify_time = 0.4;        // settling before rotation starts [s]
  double torque_interval = 0.01;    // sampling interval of the torque history [s]
  double surface_window = 0.1;      // free surface averaged over [duration - window, duration] [s]
  long long surface_snapshots = 5;  // snapshots averaged in that window
  long long surface_points = 41;    // abscissae of the free_surface curve
  // General drum; at their defaults the case is the paper's drum, unchanged.
  FillBy fill_by = FillBy::fill_fraction;
  double fill_volume_ml = 0.0;             // bulk fill volume [mL] (fill_by == fill_volume)
  long long particle_count = 0;            // original-particle count N0 (fill_by == particle_count)
  double fill_mass = 0.0;                  // [kg] (fill_by == fill_mass)
  SizeDistributionSpec size_distribution;  // none = monodisperse particle.radius
  DrumImageSpec image;
  DrumWallMeshSpec wall_mesh;  // none = analytic shell and end disks (drum_wall_mesh.hpp)
};

struct OutputSpec {
  std::vector<double> snapshot_times;  // [s] VTK snapshots of the particles (empty = none)
  double progress_interval = 1.0;      // wall-clock seconds between progress updates
};

// How the kernel runs, not what it simulates. "numerics.reorder_particles": slab order at list
// rebuilds (dem_core's default; x1.5 on 2 threads on the issue-16 drum, x2.1-6.4 past the cache
// at 1e5-1e6 particles, bench_dem --only scaling). Off in cases by default: a reordered run is
// another round-off realisation of the flow, and the shipped figures (Tables 1 and 3) were made
// in insertion order.
// "numerics.pair_load_order": "own_row_first" (default: the order the shipped figures were made
// in) or "ascending_first_member" (dem_core's default: 53 bytes per pair less, another round-off
// realisation; dem_core/README.md).
struct NumericsSpec {
  bool reorder_particles = false;
  dem_core::PairLoadOrder pair_load_order = dem_core::PairLoadOrder::own_row_first;
};

// docs/mesh-container.md: particles poured into the user's STL geometry, gravity -z. Every
// length is in metres except the STL files, whose unit each part states.
enum class MeshMotion { fixed, rotation, translation };

// One STL surface: fixed, or moving from `start_time` on (rotation about an axis at rpm, or
// translation at a velocity). The file is read at parse time (errors before any output).
struct MeshPartSpec {
  std::string name;
  std::string stl;   // path as written in the case file (relative to the case file's folder)
  std::string unit;  // length unit of the STL: "m", "cm", "mm", "um" or "in"
  MeshMotion motion = MeshMotion::fixed;
  std::array<double, 3> axis_point{};                                // [m], rotation
  std::array<double, 3> axis_direction{0, 0, 1};                     // rotation, right-handed
  double rpm = 0.0;                                                  // [rev/min], rotation
  std::array<double, 3> velocity{};                                  // [m/s], translation
  double start_time = 0.0;                                           // [s] the motion starts (fixed before)
  std::shared_ptr<const std::vector<dem_core::Triangle>> triangles;  // [m], resolved at parse time
  std::uint64_t content_hash = 0;                                    // FNV-1a of the triangles (result keys)
};

// heap_angle: surface of the resting heap on a pedestal, fitted over a radial window.
struct HeapAngleSpec {
  bool enabled = false;
  std::array<double, 2> center{};   // heap axis (x, y) [m]
  double base_z = 0.0;              // pedestal top [m]: particles below it are not the heap
  double r_min = 0.0, r_max = 0.0;  // radial window of the fit [m]
  long long bins = 8;               // annuli in the window
  double rest_speed = 0.05;         // particles faster than this [m/s] are not the heap
};

// discharge_mass: mass of particles whose centre is below plane_z.
struct DischargeSpec {
  bool enabled = false;
  double plane_z = 0.0;           // [m]
  double orifice_diameter = 0.0;  // [m], optional: Beverloo reference rate in the summary (0 = none)
};

// moving_part_torque: drive torque of one rotating part about its axis.
struct PartTorqueSpec {
  bool enabled = false;
  std::string mesh;  // name of a rotating part
};

struct MeshContainerSpec {
  std::vector<MeshPartSpec> meshes;
  std::array<double, 3> fill_lower{}, fill_upper{};  // fill box [m]
  long long particle_count = 500;
  long long fill_seed = 1;
  SizeDistributionSpec size_distribution;  // none = particle.radius (with particle.radius_spread)
  double duration = 1.0;                   // simulated time [s] from the pour on
  double output_interval = 0.01;           // curve sampling interval [s]
  HeapAngleSpec heap_angle;
  DischargeSpec discharge_mass;
  PartTorqueSpec moving_part_torque;
};

enum class CaseKind { pellet_compression, rotary_drum, mesh_container };

struct CaseSpec {
  CaseKind kind = CaseKind::pellet_compression;
  std::string description;
  MaterialSpec material;
  // "contact.law": lsdyna_linear (default; docs/spec.md 1) or hertz_mindlin (rotary_drum only). Under
  // hertz_mindlin the case gives contact.restitution/frics/fricr and the wall's material
  // (wall.youngs_modulus, wall.poisson_ratio) with wall.frics and wall.fricd (= wall rolling
  // friction, key "fricr" in the file); restitution is shared by pairs and walls.
  dem_core::ContactLawKind law = dem_core::ContactLawKind::lsdyna_linear;
  // Hertz: wall sliding and rolling friction follow the particle values (also under overrides).
  bool wall_friction_as_particles = false;
  // With the tie: wall FRICS = ratio x particle FRICS ("wall_contact.friction_ratio", 1 = the
  // tie itself), so wall friction can be released from the particles' as a parameter.
  double wall_friction_ratio = 1.0;
  ContactSpec contact;
  WallContactSpec wall;
  TimeStepSpec time_step;
  OutputSpec output;
  NumericsSpec numerics;
  PelletSpec pellet;                 // used when kind == pellet_compression
  DrumSpec drum;                     // used when kind == rotary_drum
  MeshContainerSpec mesh_container;  // used when kind == mesh_container
};

// `base_dir`: folder against which relative file references (size CSV) resolve; empty = cwd.
CaseSpec parse_case(const nlohmann::json& document, const std::filesystem::path& base_dir = {});
nlohmann::json to_json(const CaseSpec& spec);

// to_json without the effects-library fields that are at their off values (the effect rows of
// the parameter table, cases/parameter_table.hpp: particle.radius_spread = 0,
// contact.unloading_stiffness_ratio = 1, contact.surface_energy = 0, contact.stiffness_exponent = 1): the text of a
// case without effects is the text it had before the effects existed, so cache keys built from it (fills, results) stay
// valid.
nlohmann::json to_key_json(const CaseSpec& spec);

// Reads a case file; a missing file or malformed JSON is an error naming the file.
nlohmann::json read_case_json(const std::string& path);

// Applies "name=value" overrides to a case document before parsing. `name` is an identified
// parameter (a row of the parameter table, cases/parameter_table.hpp; docs/parameters.md) or a
// dotted path ("pellet.piston_speed"); `value` is JSON (a number, true/false or a
// quoted string; a bare word is taken as a string).
void apply_setting(nlohmann::json& document, const std::string& assignment);

// Dotted JSON path of an identified parameter name in an lsdyna_linear case file (the row's
// case_path: "normk" -> "contact.normk", "wall_damp" -> "wall_contact.damp"); empty when the
// name is not a parameter.
std::string parameter_path(const std::string& name);

// The identified-parameter names: the rows of the parameter table, in its order (contact, wall,
// effects, Hertz restitution, drum fill amounts; see docs/parameters.md).
const std::vector<std::string>& parameter_names();

// "lsdyna_linear" / "hertz_mindlin".
std::string to_string(dem_core::ContactLawKind law);
// "own_row_first" / "ascending_first_member" (the spellings of "numerics.pair_load_order").
std::string to_string(dem_core::PairLoadOrder order);

}  // namespace demfit::cases
