// Mesh walls against analytic walls and analytic contact geometry: a flat mesh face gives the
// analytic plane's forces, an edge or corner of a convex mesh pushes along the line from the
// edge/corner to the centre with the law's force for that overlap (one contact, not one per
// triangle), an inside corner gives the three planes' contacts, a sphere rolling across the shared
// edge of a flat floor sees no bump.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "demfit/dem_core/drum_mesh.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "mesh_shapes.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

constexpr double kBallRadius = 2.0e-3;  // the sphere [m]
constexpr double kHalfSide = 0.05;      // half the side of the box and of the floor [m]

SimulationSettings settings_with_friction() {
  SimulationSettings s;
  s.gravity = {0, 0, -kGravity};
  s.contact.frics = 0.5;  // rotation on
  s.reorder_particles = false;
  s.time_step = 2.0e-5;  // the same step in both runs
  return s;
}

const WallContactParameters rough_damped{0.4, 0.0, 0.3, 1.0};  // FRICS, FRICD (rolling), DAMP, SFP

/// Wall spring k_w = SFP NORMK K R of the linear law [N/m].
double wall_stiffness(const Simulation& sim) {
  return 1.0 * sim.settings().contact.normk * kTestMaterial.bulk_modulus * kBallRadius;
}

}  // namespace

TEST_CASE("A sphere dropped on a flat face of a meshed box moves exactly as on the analytic plane",
          "[dem_core][mesh]") {
  Simulation meshed(settings_with_friction()), analytic(settings_with_friction());
  for (Simulation* s : {&meshed, &analytic}) s->add_material(kTestMaterial);
  meshed.add_wall(
      mesh_wall(box_triangles({-kHalfSide, -kHalfSide, -kHalfSide}, {kHalfSide, kHalfSide, 0}), rough_damped));
  WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  plane.contact = rough_damped;
  analytic.add_wall(plane);
  for (Simulation* s : {&meshed, &analytic})  // oblique, spinning: normal, friction and rolling loads
    s->add_particle({0.013, -0.007, 1.5 * kBallRadius}, kBallRadius, 0, {0.3, -0.1, -0.5}, {20.0, 5.0, -3.0});
  std::size_t contact_steps = 0;
  double largest_rise = 0.0;
  for (int step = 0; step < 5000; ++step) {
    meshed.step();
    analytic.step();
    contact_steps += analytic.wall_contact_count();
    largest_rise = std::max(largest_rise, analytic.velocities()[0].z);
    REQUIRE(meshed.positions()[0] == analytic.positions()[0]);
    REQUIRE(meshed.velocities()[0] == analytic.velocities()[0]);
    REQUIRE(meshed.angular_velocities()[0] == analytic.angular_velocities()[0]);
    REQUIRE(meshed.wall_force(0) == analytic.wall_force(0));
  }
  CHECK(contact_steps > 50);    // it hit the face
  CHECK(largest_rise > 0.1);     // and rebounded
}

TEST_CASE("A sphere striking a convex edge of a meshed box is pushed along the line from the edge to its centre",
          "[dem_core][mesh]") {
  // Frictionless, undamped: the force on the sphere is k_w (r - d) (c - q)/d with q the closest
  // point of the box edge {x = half, z = 0}. One contact: the two triangles
  // holding the edge (top and side face) must not both push (that would double the force).
  SimulationSettings s = settings_with_friction();
  s.contact.frics = 0.0;
  s.time_step = 2.0e-6;  // ~100 steps per impact
  Simulation sim(s);
  sim.add_material(kTestMaterial);
  sim.add_wall(mesh_wall(box_triangles({-kHalfSide, -kHalfSide, -kHalfSide}, {kHalfSide, kHalfSide, 0}), {}));
  const double v0 = 0.4;
  sim.add_particle({kHalfSide + 0.4 * kBallRadius, 0.01, 1.2 * kBallRadius}, kBallRadius, 0, {0, 0, -v0});
  const double k = wall_stiffness(sim);
  int contact_steps = 0;
  for (int step = 0; step < 2000; ++step) {
    sim.step();
    const Vec3 c = sim.positions()[0];
    const Vec3 q{kHalfSide, c.y, 0.0};
    const double d = norm(c - q);
    if (d >= kBallRadius || c.z <= 0.0 || c.x <= kHalfSide) {  // away from the edge's region: no contact expected
      if (c.z > 0.0 && c.x > kHalfSide) CHECK(sim.wall_contact_count() == 0);
      continue;
    }
    ++contact_steps;
    REQUIRE(sim.wall_contact_count() == 1);
    const Vec3 expected_on_wall = -(k * (kBallRadius - d) / d) * (c - q);
    const Vec3 got = sim.wall_force(0);
    INFO("step " << step << " force " << got.x << " " << got.y << " " << got.z);
    CHECK(norm(got - expected_on_wall) <= 1e-9 * norm(expected_on_wall));
  }
  CHECK(contact_steps > 20);
  // Elastic and frictionless: kinetic plus potential energy per unit mass is kept, to the
  // integrator's error.
  const Vec3 v = sim.velocities()[0];
  const double energy = 0.5 * norm2(v) + kGravity * sim.positions()[0].z;
  CHECK(energy == Approx(0.5 * v0 * v0 + kGravity * 1.2 * kBallRadius).epsilon(1e-3));
  CHECK(v.x > 0.0);  // deflected off the edge, outwards
}

TEST_CASE("A sphere striking a corner of a meshed box is pushed along the line from the corner to its centre",
          "[dem_core][mesh]") {
  // The corner (half, half, 0) is held by five of the box's triangles: one contact.
  SimulationSettings s = settings_with_friction();
  s.contact.frics = 0.0;
  s.time_step = 2.0e-6;  // ~100 steps per impact
  Simulation sim(s);
  sim.add_material(kTestMaterial);
  sim.add_wall(mesh_wall(box_triangles({-kHalfSide, -kHalfSide, -kHalfSide}, {kHalfSide, kHalfSide, 0}), {}));
  sim.add_particle({kHalfSide + 0.3 * kBallRadius, kHalfSide + 0.2 * kBallRadius, 1.2 * kBallRadius}, kBallRadius, 0,
                   {0, 0, -0.4});
  const double k = wall_stiffness(sim);
  const Vec3 corner{kHalfSide, kHalfSide, 0};
  int contact_steps = 0;
  for (int step = 0; step < 2000; ++step) {
    sim.step();
    const Vec3 c = sim.positions()[0];
    const double d = norm(c - corner);
    if (d >= kBallRadius) {
      CHECK(sim.wall_contact_count() == 0);
      continue;
    }
    ++contact_steps;
    REQUIRE(sim.wall_contact_count() == 1);
    const Vec3 expected_on_wall = -(k * (kBallRadius - d) / d) * (c - corner);
    CHECK(norm(sim.wall_force(0) - expected_on_wall) <= 1e-9 * norm(expected_on_wall));
  }
  CHECK(contact_steps > 20);
}

TEST_CASE("A sphere thrown into an inside corner of a meshed box moves as against the three analytic planes",
          "[dem_core][mesh]") {
  // Inside the box (contact is two-sided): floor and two side walls, three contacts at once. The
  // analytic walls add their loads in wall order, the mesh deepest first: round-off apart.
  SimulationSettings settings = settings_with_friction();
  settings.gravity = {-4.0, -3.0, -kGravity};  // pulls into the corner: three contacts at rest
  Simulation meshed(settings), analytic(settings);
  for (Simulation* s : {&meshed, &analytic}) s->add_material(kTestMaterial);
  meshed.add_wall(
      mesh_wall(box_triangles({-kHalfSide, -kHalfSide, -kHalfSide}, {kHalfSide, kHalfSide, kHalfSide}), rough_damped));
  for (const Vec3& n : {Vec3{0, 0, 1}, Vec3{1, 0, 0}, Vec3{0, 1, 0}}) {
    WallSpec plane{PlaneGeometry{-kHalfSide * n, n}};
    plane.contact = rough_damped;
    analytic.add_wall(plane);
  }
  for (Simulation* s : {&meshed, &analytic})
    s->add_particle({-kHalfSide + 1.3 * kBallRadius, -kHalfSide + 1.2 * kBallRadius, -kHalfSide + 1.1 * kBallRadius},
                    kBallRadius, 0, {-0.05, -0.02, 0.03}, {3, -2, 1});
  std::size_t most_contacts = 0;
  for (int step = 0; step < 5000; ++step) {
    meshed.step();
    analytic.step();
    most_contacts = std::max(most_contacts, analytic.wall_contact_count());
    REQUIRE(meshed.wall_contact_count() == analytic.wall_contact_count());
    const Vec3 dx = meshed.positions()[0] - analytic.positions()[0];
    REQUIRE(norm(dx) <= 1e-12 * kHalfSide);
    REQUIRE(norm(meshed.velocities()[0] - analytic.velocities()[0]) <= 1e-9 * (norm(analytic.velocities()[0]) + 1e-6));
  }
  CHECK(most_contacts == 3);
}

TEST_CASE("A sphere rolling across the shared edge of a flat two-triangle floor keeps its speed and its loads",
          "[dem_core][mesh]") {
  // Rolling without slip on a flat floor keeps the speed (no rolling friction); at equilibrium
  // overlap m g / k_w nothing moves vertically. The path y = 0.003 crosses the diagonal edge at
  // x = 0.003. The loads (normal and the tangential spring's) must match the analytic plane's
  // at every step: a reset tangential history or a double contact at the edge would show.
  for (const double spin_fraction : {1.0, 0.5}) {  // rolling, and sliding into rolling
    Simulation meshed(settings_with_friction()), analytic(settings_with_friction());
    for (Simulation* s : {&meshed, &analytic}) s->add_material(kTestMaterial);
    meshed.add_wall(mesh_wall(two_triangle_floor(kHalfSide), rough_damped));
    WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
    plane.contact = rough_damped;
    analytic.add_wall(plane);
    const double v = 0.1, overlap = sphere_mass(kBallRadius) * kGravity / wall_stiffness(meshed);
    for (Simulation* s : {&meshed, &analytic})
      // No slip at the contact point, r - overlap below the centre.
      s->add_particle({-0.01, 0.003, kBallRadius - overlap}, kBallRadius, 0, {v, 0, 0},
                      {0, spin_fraction * v / (kBallRadius - overlap), 0});
    double largest_difference = 0.0, normal_min = 1e9, normal_max = 0.0;
    while (meshed.positions()[0].x < 0.015) {
      meshed.step();
      analytic.step();
      REQUIRE(meshed.wall_contact_count() == 1);
      const Vec3 f = meshed.wall_force(0);
      largest_difference = std::max(largest_difference, norm(f - analytic.wall_force(0)) / norm(analytic.wall_force(0)));
      normal_min = std::min(normal_min, -f.z);
      normal_max = std::max(normal_max, -f.z);
    }
    INFO("spin fraction " << spin_fraction << " largest relative load difference " << largest_difference);
    CHECK(largest_difference <= 1e-9);
    const double speed = norm(meshed.velocities()[0]), analytic_speed = norm(analytic.velocities()[0]);
    CHECK(std::abs(speed - analytic_speed) <= 1e-9 * analytic_speed);
    if (spin_fraction == 1.0) {
      CHECK(std::abs(speed - v) <= 1e-6 * v);                                  // no bump, no loss
      CHECK((normal_max - normal_min) <= 1e-6 * sphere_mass(kBallRadius) * kGravity);  // normal force continuous
    }
  }
}

TEST_CASE("A sphere on a finely triangulated flat floor feels the analytic plane's loads across every edge and vertex",
          "[dem_core][mesh]") {
  // 8 x 8 squares, each split along alternating diagonals: the sphere (radius 2 mm, squares
  // 5 mm) crosses edges and passes near vertices where six or eight triangles meet.
  std::vector<Triangle> floor;
  const int n = 8;
  const double w = 0.005, x0 = -0.5 * n * w;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 a{x0 + i * w, x0 + j * w, 0}, b{x0 + (i + 1) * w, x0 + j * w, 0};
      const Vec3 c{x0 + (i + 1) * w, x0 + (j + 1) * w, 0}, d{x0 + i * w, x0 + (j + 1) * w, 0};
      if ((i + j) % 2 == 0) floor.insert(floor.end(), {{a, b, c}, {a, c, d}});
      else floor.insert(floor.end(), {{a, b, d}, {b, c, d}});
    }
  Simulation meshed(settings_with_friction()), analytic(settings_with_friction());
  for (Simulation* s : {&meshed, &analytic}) s->add_material(kTestMaterial);
  meshed.add_wall(mesh_wall(floor, rough_damped));
  WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  plane.contact = rough_damped;
  analytic.add_wall(plane);
  for (Simulation* s : {&meshed, &analytic})  // sliding diagonally through the vertex (0, 0)
    s->add_particle({-0.012, -0.0121, 0.99 * kBallRadius}, kBallRadius, 0, {0.1, 0.1, 0}, {0, 0, 0});
  double largest_difference = 0.0;
  while (meshed.positions()[0].x < 0.012) {
    meshed.step();
    analytic.step();
    REQUIRE(meshed.wall_contact_count() == analytic.wall_contact_count());
    const double f = norm(analytic.wall_force(0));
    if (f > 0.0) largest_difference = std::max(largest_difference, norm(meshed.wall_force(0) - analytic.wall_force(0)) / f);
  }
  INFO("largest relative load difference " << largest_difference);
  CHECK(largest_difference <= 1e-9);
  CHECK(norm(meshed.positions()[0] - analytic.positions()[0]) <= 1e-12);
}

TEST_CASE("A mesh wall turns and translates with its prescribed motion like the analytic plane", "[dem_core][mesh]") {
  // A turntable (rotation about +z through (0.01, 0, 0)) then a lift (translation +z): the
  // sphere is carried by friction; the mesh frame turns with the wall and keeps the plane's loads.
  Simulation meshed(settings_with_friction()), analytic(settings_with_friction());
  for (Simulation* s : {&meshed, &analytic}) s->add_material(kTestMaterial);
  WallSpec mesh = mesh_wall(two_triangle_floor(kHalfSide), rough_damped);
  WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  plane.contact = rough_damped;
  const RotatingMotion turn{{0.01, 0, 0}, {0, 0, 1}, 4.0};
  mesh.motion = plane.motion = turn;
  meshed.add_wall(mesh);
  analytic.add_wall(plane);
  const double overlap = sphere_mass(kBallRadius) * kGravity / wall_stiffness(meshed);
  for (Simulation* s : {&meshed, &analytic}) s->add_particle({0.03, 0.0, kBallRadius - overlap}, kBallRadius);
  for (Simulation* s : {&meshed, &analytic}) s->run_until(0.3);
  // Carried around the turntable axis: the angle swept is a good part of 4 rad/s x 0.3 s.
  const Vec3 x = meshed.positions()[0];
  CHECK(std::atan2(x.y, x.x - 0.01) > 0.3);
  for (Simulation* s : {&meshed, &analytic}) s->set_wall_motion(0, TranslatingMotion{{0, 0, 0.05}});
  for (Simulation* s : {&meshed, &analytic}) s->run_until(0.4);
  CHECK(meshed.positions()[0].z > 0.004);  // lifted about 5 mm
  CHECK(norm(meshed.positions()[0] - analytic.positions()[0]) <= 1e-9 * kHalfSide);
  CHECK(norm(meshed.velocities()[0] - analytic.velocities()[0]) <= 1e-7 * norm(analytic.velocities()[0]));
  CHECK(meshed.wall_force(0).z == Approx(analytic.wall_force(0).z).epsilon(1e-7));
}

TEST_CASE("A sphere in a shallow concave crease feels one contact with the deeper face's force", "[dem_core][mesh]") {
  // Two faces meeting along the y axis in a valley of 2 x 3 degrees (a polygonal drum shell's
  // crease): near the crease the sphere overlaps both planes by almost the same depth; one
  // contact, the deeper, is the rule (triangle_mesh.hpp, rule 3), so the force is k_w times the
  // larger overlap (equal overlaps at the crease: the force passes continuously to the other face).
  const double a = 3.0 * std::numbers::pi / 180.0, t = kHalfSide * std::tan(a);
  const std::vector<Triangle> valley{
      {Vec3{-kHalfSide, -kHalfSide, t}, Vec3{0, -kHalfSide, 0}, Vec3{0, kHalfSide, 0}},
      {Vec3{-kHalfSide, -kHalfSide, t}, Vec3{0, kHalfSide, 0}, Vec3{-kHalfSide, kHalfSide, t}},
      {Vec3{0, -kHalfSide, 0}, Vec3{kHalfSide, -kHalfSide, t}, Vec3{kHalfSide, kHalfSide, t}},
      {Vec3{0, -kHalfSide, 0}, Vec3{kHalfSide, kHalfSide, t}, Vec3{0, kHalfSide, 0}}};
  const Vec3 left{std::sin(a), 0, std::cos(a)}, right{-std::sin(a), 0, std::cos(a)};  // planes through 0
  SimulationSettings s = settings_with_friction();
  s.gravity = {0, 0, 0};
  s.contact.frics = 0.0;
  int both_faces_overlapped = 0;  // offsets where counting both faces would have doubled the force
  for (int k = -10; k <= 10; ++k) {
    Simulation sim(s);
    sim.add_material(kTestMaterial);
    sim.add_wall(mesh_wall(valley, {}));
    sim.add_particle({0.02 * kBallRadius * k, 0.0, 0.99 * kBallRadius}, kBallRadius);
    sim.step();
    const Vec3 c = sim.positions()[0];
    const double deeper = std::max(kBallRadius - dot(c, left), kBallRadius - dot(c, right));
    const double expected = wall_stiffness(sim) * deeper;
    INFO("offset " << 0.02 * k << " r");
    REQUIRE(sim.wall_contact_count() == 1);
    CHECK(norm(sim.wall_force(0)) == Approx(expected).epsilon(1e-9));
    const double shallower = std::min(kBallRadius - dot(c, left), kBallRadius - dot(c, right));
    if (shallower > 0.5 * deeper) ++both_faces_overlapped;
  }
  CHECK(both_faces_overlapped >= 3);
}

TEST_CASE("Runs with a rotating mesh wall are bit-identical between 1 and 2 threads", "[dem_core][mesh][determinism]") {
  auto run = [](int threads) {
    SimulationSettings s = settings_with_friction();
    s.threads = threads;
    s.reorder_particles = true;  // particle order changes at rebuilds: slots and histories follow
    Simulation sim(s);
    sim.add_material(kTestMaterial);
    WallSpec box = mesh_wall(box_triangles({-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}), rough_damped);
    box.motion = RotatingMotion{{0, 0, 0}, {1, 0, 0}, 3.0};  // a tumbling box: contacts move across edges
    sim.add_wall(box);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 4; ++k)
          sim.add_particle({-0.006 + 0.004 * i, -0.006 + 0.004 * j, -0.006 + 0.004 * k}, kBallRadius);
    std::vector<double> torques;  // every 100 steps, 2000 in all
    std::size_t most_contacts = 0;
    for (int chunk = 0; chunk < 20; ++chunk) {
      sim.run_steps(100);
      torques.push_back(sim.wall_torque(0));
      most_contacts = std::max(most_contacts, sim.wall_contact_count());
    }
    CHECK(most_contacts >= 16);  // the bottom layer at least
    return std::pair{std::vector<Vec3>(sim.positions().begin(), sim.positions().end()), torques};
  };
  const auto one = run(1), two = run(2);
  CHECK(one.first == two.first);
  CHECK(one.second == two.second);
  CHECK(std::any_of(one.second.begin(), one.second.end(), [](double t) { return t != 0.0; }));
}

TEST_CASE("A sphere pressed into a face next to a convex edge or corner feels only the face", "[dem_core][mesh]") {
  // Overlap 5 % of r, centre 0.2 r inside the edge: the side faces' triangles hold the edge (and
  // corner) within r of the centre, at a point other than the face contact and with a normal
  // 12 degrees off the face's. Rule 2 of triangle_mesh.hpp drops them: the loads are the plane's.
  for (const Vec3& at : {Vec3{kHalfSide - 0.2 * kBallRadius, 0.0, 0.95 * kBallRadius},
                         Vec3{kHalfSide - 0.2 * kBallRadius, kHalfSide - 0.15 * kBallRadius, 0.95 * kBallRadius}}) {
    SimulationSettings s = settings_with_friction();
    s.gravity = {0, 0, 0};
    Simulation meshed(s), analytic(s);
    for (Simulation* sim : {&meshed, &analytic}) sim->add_material(kTestMaterial);
    meshed.add_wall(
        mesh_wall(box_triangles({-kHalfSide, -kHalfSide, -kHalfSide}, {kHalfSide, kHalfSide, 0}), rough_damped));
    WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
    plane.contact = rough_damped;
    analytic.add_wall(plane);
    for (Simulation* sim : {&meshed, &analytic}) sim->add_particle(at, kBallRadius);
    for (int step = 0; step < 5; ++step) {
      meshed.step();
      analytic.step();
      REQUIRE(meshed.wall_contact_count() == 1);
      REQUIRE(meshed.wall_force(0) == analytic.wall_force(0));
    }
  }
}

TEST_CASE("A sphere's contacts from its candidate triangles equal those found through the mesh's cells",
          "[dem_core][mesh]") {
  // The candidate list of a slot is built at one centre with reach r + margin and used at centres
  // up to `margin` away: the contacts must be those of the whole mesh, to the bit.
  const TriangleMesh mesh(drum_mesh_triangles({0.05, 0.02, 0.3, 90, 2, 3}));
  const double radius = 1.5e-3, margin = 0.4e-3;
  std::uint64_t state = 12345;
  auto uniform = [&state] {  // splitmix64 -> [0, 1)
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  int with_contacts = 0, several = 0;
  std::vector<std::uint32_t> candidates;
  for (int k = 0; k < 4000; ++k) {
    // Centres near the shell, the caps and the rim where they meet.
    const double angle = 2.0 * std::numbers::pi * uniform();
    const double rho = 0.05 - 2.0 * radius * uniform();
    const double z = uniform() < 0.5 ? 0.02 * uniform() : (uniform() < 0.5 ? 2.0 * radius * uniform()
                                                                              : 0.02 - 2.0 * radius * uniform());
    const Vec3 built{rho * std::cos(angle), rho * std::sin(angle), z};
    const Vec3 step{uniform() - 0.5, uniform() - 0.5, uniform() - 0.5};
    const Vec3 now = built + (margin * 0.999 / std::sqrt(norm2(step))) * step;  // moved just under margin
    candidates.clear();
    mesh.triangles_within(built, radius + margin, candidates);
    MeshContact from_cells[8], from_list[8];
    const int n_cells = mesh.contacts(now, radius, from_cells, 8);
    const int n_list = mesh.contacts(now, radius, candidates, from_list, 8);
    REQUIRE(n_list == n_cells);
    for (int c = 0; c < n_cells; ++c) {
      REQUIRE(from_list[c].triangle == from_cells[c].triangle);
      REQUIRE(from_list[c].overlap == from_cells[c].overlap);
      REQUIRE(from_list[c].normal.x == from_cells[c].normal.x);
      REQUIRE(from_list[c].normal.y == from_cells[c].normal.y);
      REQUIRE(from_list[c].normal.z == from_cells[c].normal.z);
    }
    with_contacts += n_cells > 0;
    several += n_cells > 1;
  }
  CHECK(with_contacts > 1000);  // the sample reaches the surface, its edges and the rim
  CHECK(several > 20);
}
