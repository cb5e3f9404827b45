// Wall geometry tests, wall kinematics and wall construction (docs/spec.md 1, particle-to-wall).
#include "demfit/dem_core/wall.hpp"

#include <cmath>
#include <stdexcept>

#include "validation.hpp"
#include "wall_mesh.hpp"

namespace demfit::dem_core {
namespace {

WallProximity plane_proximity(const Vec3& point, const Vec3& normal, const Vec3& c, double r) {
  const double d = dot(c - point, normal);
  if (d >= r || d <= -r) return {};
  return {true, -normal, r - d};
}

WallProximity disk_proximity(const DiskGeometry& g, const Vec3& c, double r) {
  const Vec3 rel = c - g.center;
  const double d = dot(rel, g.normal);
  const Vec3 radial = rel - d * g.normal;
  const double rho2 = norm2(radial);
  if (rho2 <= g.radius * g.radius) return plane_proximity(g.center, g.normal, c, r);
  // Beyond the rim: closest point of the rim circle (two-sided edge contact).
  const Vec3 rim = g.center + (g.radius / std::sqrt(rho2)) * radial;
  const Vec3 to_center = c - rim;
  const double dist2 = norm2(to_center);
  if (dist2 >= r * r || dist2 == 0.0) return {};
  const double dist = std::sqrt(dist2);
  return {true, (-1.0 / dist) * to_center, r - dist};
}

WallProximity cylinder_proximity(const CylinderGeometry& g, const Vec3& c, double r) {
  const Vec3 rel = c - g.base_center;
  const double s = dot(rel, g.axis);
  if (s < 0.0 || s > g.length) return {};
  const Vec3 radial = rel - s * g.axis;
  const double rho2 = norm2(radial);
  const double inner = g.radius - r;  // touching when rho > R_c - r
  if (inner > 0.0 && rho2 <= inner * inner) return {};
  if (rho2 == 0.0) return {};
  const double rho = std::sqrt(rho2);
  return {true, (1.0 / rho) * radial, rho + r - g.radius};
}

/// Rodrigues rotation of v about unit k by angle theta.
Vec3 rotate(const Vec3& v, const Vec3& k, double cos_t, double sin_t) {
  return v * cos_t + cross(k, v) * sin_t + k * (dot(k, v) * (1.0 - cos_t));
}

}  // namespace

WallProximity wall_proximity(const WallGeometry& geometry, const Vec3& center, double radius) {
  return std::visit(
      [&](const auto& g) -> WallProximity {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, PlaneGeometry>)
          return plane_proximity(g.point, g.normal, center, radius);
        else if constexpr (std::is_same_v<G, DiskGeometry>)
          return disk_proximity(g, center, radius);
        else if constexpr (std::is_same_v<G, CylinderGeometry>)
          return cylinder_proximity(g, center, radius);
        else {
          WallProximity deepest;
          mesh_wall_contacts(g, center, radius, &deepest, 1);
          return deepest;
        }
      },
      geometry);
}

bool wall_may_touch(const WallGeometry& geometry, const Vec3& center, double radius, double margin) {
  if (const auto* g = std::get_if<CylinderGeometry>(&geometry)) {
    // The axial window [0, length] has no radius margin in the contact test, so widen it here.
    const Vec3 rel = center - g->base_center;
    const double s = dot(rel, g->axis);
    if (s < -margin || s > g->length + margin) return false;
    const double inner = g->radius - radius - margin;
    return inner <= 0.0 || norm2(rel - s * g->axis) > inner * inner;
  }
  if (const auto* m = std::get_if<MeshGeometry>(&geometry))
    return m->mesh->any_within(mesh_frame_point(*m, center), radius + margin);
  return wall_proximity(geometry, center, radius + margin).touching;
}

bool wall_distances_rigid(const Wall& wall) {
  const auto* m = std::get_if<RotatingMotion>(&wall.motion);
  if (m == nullptr || m->angular_velocity == 0.0) return true;
  // A polygonal surface has no exact symmetry axis: a rotating mesh changes distances.
  if (std::holds_alternative<MeshGeometry>(wall.geometry)) return false;
  const Vec3& u = m->axis_direction;
  constexpr double tolerance = 1e-9;
  auto parallel = [&](const Vec3& d) { return norm(cross(d, u)) < tolerance; };
  auto on_axis = [&](const Vec3& p) {
    return norm(cross(p - m->axis_point, u)) < tolerance * (1.0 + norm(p - m->axis_point));
  };
  return std::visit(
      [&](const auto& g) -> bool {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, PlaneGeometry>)
          return parallel(g.normal);
        else if constexpr (std::is_same_v<G, DiskGeometry>)
          return parallel(g.normal) && on_axis(g.center);
        else if constexpr (std::is_same_v<G, CylinderGeometry>)
          return parallel(g.axis) && on_axis(g.base_center);
        else
          return false;
      },
      wall.geometry);
}

Vec3 wall_velocity_at(const Wall& wall, const Vec3& point) {
  if (const auto* t = std::get_if<TranslatingMotion>(&wall.motion)) return t->velocity;
  if (const auto* m = std::get_if<RotatingMotion>(&wall.motion))
    return cross(m->angular_velocity * m->axis_direction, point - m->axis_point);
  return {};
}

Vec3 wall_angular_velocity(const Wall& wall) {
  if (const auto* m = std::get_if<RotatingMotion>(&wall.motion)) return m->angular_velocity * m->axis_direction;
  return {};
}

void advance_wall(Wall& wall, double dt) {
  if (const auto* t = std::get_if<TranslatingMotion>(&wall.motion)) {
    const Vec3 shift = t->velocity * dt;
    std::visit(
        [&](auto& g) {
          using G = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<G, PlaneGeometry>)
            g.point += shift;
          else if constexpr (std::is_same_v<G, DiskGeometry>)
            g.center += shift;
          else if constexpr (std::is_same_v<G, CylinderGeometry>)
            g.base_center += shift;
          else
            g.origin += shift;
        },
        wall.geometry);
    wall.torque_axis.point += shift;
    wall.displacement += shift;
  } else if (const auto* m = std::get_if<RotatingMotion>(&wall.motion)) {
    const double theta = m->angular_velocity * dt;
    if (theta == 0.0) return;
    const double c = std::cos(theta), s = std::sin(theta);
    const Vec3& k = m->axis_direction;
    const Vec3& a = m->axis_point;
    auto move_point = [&](Vec3& p) { p = a + rotate(p - a, k, c, s); };
    auto move_direction = [&](Vec3& d) { d = normalized(rotate(d, k, c, s)); };
    std::visit(
        [&](auto& g) {
          using G = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<G, PlaneGeometry>) {
            move_point(g.point);
            move_direction(g.normal);
          } else if constexpr (std::is_same_v<G, DiskGeometry>) {
            move_point(g.center);
            move_direction(g.normal);
          } else if constexpr (std::is_same_v<G, CylinderGeometry>) {
            move_point(g.base_center);
            move_direction(g.axis);
          } else {
            move_point(g.origin);
            g.axis_x = rotate(g.axis_x, k, c, s);
            g.axis_y = rotate(g.axis_y, k, c, s);
            orthonormalize(g);  // no drift of the frame over many steps
          }
        },
        wall.geometry);
    move_point(wall.torque_axis.point);
    move_direction(wall.torque_axis.direction);
    wall.rotation_angle += theta;
  }
}

Wall make_wall(const WallSpec& spec) {
  validate(spec.contact);
  Wall wall;
  wall.geometry = spec.geometry;
  wall.motion = spec.motion;
  wall.contact = spec.contact;
  wall.name = spec.name;
  Axis own_axis;
  std::visit(
      [&](auto& g) {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, PlaneGeometry>) {
          require_finite("plane.point [m]", g.point);
          g.normal = require_direction("plane.normal", g.normal);
          own_axis = {g.point, g.normal};
        } else if constexpr (std::is_same_v<G, DiskGeometry>) {
          require_finite("disk.center [m]", g.center);
          g.normal = require_direction("disk.normal", g.normal);
          require_positive("disk.radius [m]", g.radius);
          own_axis = {g.center, g.normal};
        } else if constexpr (std::is_same_v<G, CylinderGeometry>) {
          require_finite("cylinder.base_center [m]", g.base_center);
          g.axis = require_direction("cylinder.axis", g.axis);
          require_positive("cylinder.radius [m]", g.radius);
          require_positive("cylinder.length [m]", g.length);
          own_axis = {g.base_center, g.axis};
        } else {
          validate_mesh_geometry(g);
          own_axis = {g.origin, g.axis_z};
        }
      },
      wall.geometry);
  std::visit(
      [&](auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, TranslatingMotion>) {
          require_finite("wall motion velocity [m/s]", m.velocity);
        } else if constexpr (std::is_same_v<M, RotatingMotion>) {
          require_finite("wall rotation axis_point [m]", m.axis_point);
          m.axis_direction = require_direction("wall rotation axis_direction", m.axis_direction);
          require_finite("wall rotation angular_velocity [rad/s]", m.angular_velocity);
          own_axis = {m.axis_point, m.axis_direction};
        }
      },
      wall.motion);
  if (spec.torque_axis) {
    require_finite("wall torque_axis.point [m]", spec.torque_axis->point);
    wall.torque_axis = {spec.torque_axis->point,
                        require_direction("wall torque_axis.direction", spec.torque_axis->direction)};
  } else {
    wall.torque_axis = own_axis;
  }
  return wall;
}

}  // namespace demfit::dem_core
