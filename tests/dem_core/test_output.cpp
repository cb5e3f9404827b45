// Probes and snapshot writers: files read back and compared with the simulation state.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "demfit/dem_core/probes.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "demfit/dem_core/snapshot.hpp"

using namespace demfit::dem_core;

namespace {

Simulation two_spheres_on_a_floor() {
  SimulationSettings settings;
  settings.contact.ndamp = 0.5;
  Simulation sim(settings);
  sim.add_material({1e9, 2500.0, 0.3});
  WallSpec floor{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  floor.contact.damp = 0.5;
  sim.add_wall(floor);
  sim.add_particle({0, 0, 1e-3}, 1e-3, 0, {0.01, 0, 0});
  sim.add_particle({3e-3, 0, 1.5e-3}, 1.5e-3);
  return sim;
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("Probe time series record wall force, energies and bed height and write a CSV with units",
          "[dem_core][output]") {
  Simulation sim = two_spheres_on_a_floor();
  ProbeRecorder probes;
  probes.add_wall_force("floor_force", 0, {0, 0, -1});
  probes.add_wall_torque("floor_torque", 0);
  probes.add_kinetic_energy();
  probes.add_elastic_energy();
  probes.add_bed_height("bed", {0, 0, 1}, 1.0);
  sim.run_until(
      0.05,
      [&](Simulation& s) {
        probes.record(s);
        return true;
      },
      100);
  REQUIRE(probes.times().size() > 5);
  // At rest the floor carries the weight of both spheres: sum m g (1 %).
  const double weight = (sim.masses()[0] + sim.masses()[1]) * 9.81;
  CHECK(probes.get("floor_force").values.back() == Approx(weight).epsilon(0.01));
  CHECK(probes.get("bed").values.back() == Approx(0.5 * (2e-3 + 3e-3)).epsilon(0.01));  // mean top, both
  CHECK(probes.get("kinetic_energy").values.back() == Approx(sim.kinetic_energy()));
  const auto path = std::filesystem::temp_directory_path() / "demfit_probe_test.csv";
  probes.write_csv(path.string());
  const std::string text = read_all(path);
  CHECK(text.rfind("time_s,floor_force_N,floor_torque_N_m,kinetic_energy_J,elastic_energy_J,bed_m\n", 0) == 0);
  CHECK(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) == probes.times().size() + 1);
  CHECK_THROWS_WITH(probes.get("nope"), Catch::Contains("nope"));
}

TEST_CASE("VTK and CSV snapshots contain every particle with radius and velocity", "[dem_core][output]") {
  Simulation sim = two_spheres_on_a_floor();
  sim.run_steps(10);
  const auto dir = std::filesystem::temp_directory_path();
  write_vtk_snapshot(sim, (dir / "demfit_snapshot_test.vtk").string());
  write_csv_snapshot(sim, (dir / "demfit_snapshot_test.csv").string());
  const std::string vtk = read_all(dir / "demfit_snapshot_test.vtk");
  CHECK(vtk.rfind("# vtk DataFile Version 3.0\n", 0) == 0);
  CHECK_THAT(vtk, Catch::Contains("DATASET POLYDATA") && Catch::Contains("POINTS 2 double") &&
                      Catch::Contains("SCALARS radius double 1") && Catch::Contains("VECTORS velocity double"));
  std::istringstream csv(read_all(dir / "demfit_snapshot_test.csv"));
  std::string header, row;
  std::getline(csv, header);
  CHECK(header == "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s,wx_rad_per_s,wy_rad_per_s,wz_rad_per_s");
  std::getline(csv, row);
  std::istringstream fields(row);
  double x = 0.0;
  char comma = 0;
  fields >> x >> comma;
  CHECK(x == Approx(sim.positions()[0].x).epsilon(1e-8));
  CHECK_THROWS_WITH(write_csv_snapshot(sim, "/nonexistent_dir/x.csv"), Catch::Contains("/nonexistent_dir/x.csv"));
}

TEST_CASE("Snapshots list particles in the order they were added after reordering moved them in memory",
          "[dem_core][output]") {
  SimulationSettings settings;
  settings.reorder_particles = true;  // the default, stated: the test is about it
  Simulation sim(settings);
  sim.add_material({1e9, 2500.0, 0.3});
  // Eight spheres added from far to near along x, each with its own radius: Morton order reverses
  // them in memory, the files must not.
  for (int k = 0; k < 8; ++k) sim.add_particle({0.1 * (7 - k), 0, 0}, 1e-3 * (1.0 + 0.1 * k));
  sim.run_steps(2);
  REQUIRE(sim.particles().id[0] != 0);  // reordering did move them (else this test proves nothing)
  const auto path = std::filesystem::temp_directory_path() / "demfit_snapshot_order_test.csv";
  write_csv_snapshot(sim, path.string());
  std::istringstream csv(read_all(path));
  std::string row;
  std::getline(csv, row);  // header
  for (int k = 0; k < 8; ++k) {
    REQUIRE(std::getline(csv, row));
    std::istringstream fields(row);
    double x = 0.0, y = 0.0, z = 0.0, radius = 0.0;
    char comma = 0;
    fields >> x >> comma >> y >> comma >> z >> comma >> radius;
    CHECK(radius == Approx(1e-3 * (1.0 + 0.1 * k)).epsilon(1e-8));
    CHECK(x == Approx(0.1 * (7 - k)).margin(1e-6));
  }
}

TEST_CASE("Hertz law: a sphere resting on a rigid plane has the Hertz static overlap", "[dem_core][walls]") {
  // Rigid wall: E* = E/(1 - nu^2), R* = R; m g = 4/3 E* sqrt(R) delta^{3/2}.
  const Material material{1.0e9, 2500.0, 0.3};
  const double r = 1e-3, g = 9.81;
  SimulationSettings settings;
  settings.law = ContactLawKind::hertz_mindlin;
  settings.contact.restitution = 0.3;
  Simulation sim(settings);
  sim.add_material(material);
  sim.add_wall({PlaneGeometry{{0, 0, 0}, {0, 0, 1}}});
  sim.add_particle({0, 0, r}, r);
  sim.run_until(0.02);
  const double e = 3.0 * material.bulk_modulus * (1.0 - 2.0 * material.poisson_ratio);
  const double e_star = e / (1.0 - material.poisson_ratio * material.poisson_ratio);
  const double weight = sim.masses()[0] * g;
  const double expected = std::pow(3.0 * weight / (4.0 * e_star * std::sqrt(r)), 2.0 / 3.0);
  CHECK(r - sim.positions()[0].z == Approx(expected).epsilon(0.005));
  CHECK(sim.wall_force(0).z == Approx(-weight).epsilon(0.005));
}
