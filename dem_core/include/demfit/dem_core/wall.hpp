#pragma once
// Rigid walls as data: a geometry (std::variant) plus a motion law (std::variant). Walls interact
// with particles through the particle–wall law (docs/spec.md 1, WallContactParameters) and accumulate the
// force and the torque that the particles exert on them.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/triangle_mesh.hpp"
#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

/// Infinite plane through `point`; `normal` (normalised on add) points to the side where the
/// particles are. A particle whose centre is more than one radius behind the plane is ignored.
struct PlaneGeometry {
  Vec3 point{};
  Vec3 normal{0, 0, 1};
};

/// Flat disk (e.g. a piston face or a drum end wall): centre, unit normal towards the particles,
/// radius [m]. Face contacts push along `normal` (one-sided); beyond the rim the closest rim
/// point is used.
struct DiskGeometry {
  Vec3 center{};
  Vec3 normal{0, 0, 1};
  double radius = 0.0;
};

/// Inner surface of a finite cylinder (a container or a drum shell): axis from `base_center`
/// along unit `axis` for `length` [m], inner radius [m]. Particles touch it from the inside;
/// particles whose centre lies axially outside [0, length] do not touch it (close the ends with
/// disks). No end caps are implied.
struct CylinderGeometry {
  Vec3 base_center{};
  Vec3 axis{0, 0, 1};
  double radius = 0.0;
  double length = 0.0;
};

/// A triangle surface (an STL file: read_stl) placed rigidly in the world: mesh-frame point x is
/// at origin + x.x axis_x + x.y axis_y + x.z axis_z (axes orthonormalised on add, right-handed).
/// Contact is two-sided, a sphere feels one contact per surface point it touches where
/// triangles meet, through the same wall law as the analytic walls (triangle_mesh.hpp). A
/// particle keeps up to `max_contacts` simultaneous contacts with the mesh (an inside box corner
/// needs 3), each with its own tangential history: a contact point keeps its history while its
/// normal turns continuously (e.g. when the closest triangle changes across a shared edge).
struct MeshGeometry {
  std::shared_ptr<const TriangleMesh> mesh{};  ///< shared, immutable: walls copy cheaply
  Vec3 origin{};
  Vec3 axis_x{1, 0, 0}, axis_y{0, 1, 0}, axis_z{0, 0, 1};
  int max_contacts = 3;  ///< contact slots per particle, 1..8
};

using WallGeometry = std::variant<PlaneGeometry, DiskGeometry, CylinderGeometry, MeshGeometry>;

/// Wall does not move.
struct FixedMotion {};
/// Rigid translation with a prescribed velocity [m/s] (a piston); changeable between steps.
struct TranslatingMotion {
  Vec3 velocity{};
};
/// Rigid rotation about an axis (a drum): point on the axis [m], unit direction, angular
/// velocity [rad/s], right-handed about `axis_direction`; changeable between steps.
struct RotatingMotion {
  Vec3 axis_point{};
  Vec3 axis_direction{0, 0, 1};
  double angular_velocity = 0.0;
};

using WallMotion = std::variant<FixedMotion, TranslatingMotion, RotatingMotion>;

/// An oriented axis: point [m] and unit direction.
struct Axis {
  Vec3 point{};
  Vec3 direction{0, 0, 1};
};

/// What the user gives to Simulation::add_wall.
struct WallSpec {
  WallGeometry geometry{};
  WallMotion motion = FixedMotion{};
  WallContactParameters contact{};
  /// Axis for the recorded torque. Default: the rotation axis of a rotating wall, else the
  /// geometry's own axis (plane: normal through its point; disk: normal through its centre;
  /// cylinder: its axis).
  std::optional<Axis> torque_axis{};
  std::string name{};  ///< free label used by probes and snapshots
};

/// A wall inside the simulation: current geometry and motion, and the loads of the last step.
struct Wall {
  WallGeometry geometry{};
  WallMotion motion{};
  WallContactParameters contact{};
  Axis torque_axis{};  ///< moves with the wall (translated / rotated with it)
  std::string name{};
  Vec3 displacement{};          ///< accumulated translation since the wall was added [m]
  double rotation_angle = 0.0;  ///< accumulated rotation [rad]
  // Loads exerted BY the particles ON the wall during the last force evaluation:
  Vec3 force{};         ///< [N]
  Vec3 moment{};        ///< moment about torque_axis.point [N·m]
  double torque = 0.0;  ///< moment · torque_axis.direction [N·m]
  std::size_t contact_count = 0;
};

/// Result of the particle–wall proximity test.
struct WallProximity {
  bool touching = false;
  Vec3 normal{};         ///< unit vector from the particle centre towards the wall
  double overlap = 0.0;  ///< [m], > 0 when touching
};

/// Geometric contact test of a sphere (centre [m], radius [m]) with a wall geometry (a mesh: its
/// deepest contact).
WallProximity wall_proximity(const WallGeometry& geometry, const Vec3& center, double radius);
/// Conservative candidate test for the wall contact list: true when the sphere could touch the
/// wall after particle and wall moved relative to each other by less than `margin` [m].
bool wall_may_touch(const WallGeometry& geometry, const Vec3& center, double radius, double margin);
/// True when the wall's motion leaves every particle–wall distance unchanged apart from its
/// translation (fixed, translating, or rotating about its own symmetry axis: drum shells/ends).
bool wall_distances_rigid(const Wall& wall);
/// Contacts of a sphere with a mesh wall (world frame), deepest first, at most `capacity`.
int mesh_wall_contacts(const MeshGeometry& geometry, const Vec3& center, double radius, WallProximity* out,
                       int capacity);
/// The same contacts, testing only the candidate triangles listed for the particle at the last
/// slot build (mesh_wall_candidates), which hold every triangle it can touch until the next one.
int mesh_wall_contacts(const MeshGeometry& geometry, const Vec3& center, double radius,
                       std::span<const std::uint32_t> candidates, WallProximity* out, int capacity);
/// Appends to `found` the mesh wall's triangles closer than `reach` [m] to the point (world frame).
void mesh_wall_candidates(const MeshGeometry& geometry, const Vec3& center, double reach,
                          std::vector<std::uint32_t>& found);
/// For a rotating mesh wall: the largest distance [m] of its vertices from the rotation axis
/// (its surface moves by at most that times the angle turned); 0 for every other wall.
double wall_sweep_radius(const Wall& wall);
/// Contact slots a particle gets for this wall (1; MeshGeometry::max_contacts for a mesh).
int wall_contact_slots(const WallGeometry& geometry);
/// Velocity [m/s] of the wall's material point at `point` [m].
Vec3 wall_velocity_at(const Wall& wall, const Vec3& point);
/// Angular velocity vector of the wall [rad/s] (zero unless rotating).
Vec3 wall_angular_velocity(const Wall& wall);
/// Move the wall geometry and its torque axis by its motion over dt [s].
void advance_wall(Wall& wall, double dt);
/// Validate a spec (finite numbers, positive radii/lengths, non-zero directions); normalise the
/// directions and resolve the default torque axis. Throws std::runtime_error naming the field.
Wall make_wall(const WallSpec& spec);

}  // namespace demfit::dem_core
