// The mesh_container case kind (docs/mesh-container.md): particles poured into STL geometry; the
// heap angle, discharge mass and moving-part torque curves against independent computations;
// bad input refused with a one-line error naming the field and the fix; repeatable runs.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "case_test_options.hpp"
#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"
#include "mesh_container_case.hpp"

using namespace demfit::cases;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using Point = std::array<double, 3>;
using Facet = std::array<Point, 3>;

constexpr double kPi = std::numbers::pi;

// Triangles of simple shapes, coordinates in millimetres (the files state "unit": "mm").
Point ring_point(double r, double z, int k, int n) {
  return {r * std::cos(2 * kPi * k / n), r * std::sin(2 * kPi * k / n), z};
}

std::vector<Facet> annulus(double r_in, double r_out, double z, int n) {
  std::vector<Facet> out;
  for (int k = 0; k < n; ++k) {
    const Point a = ring_point(r_in, z, k, n), b = ring_point(r_out, z, k, n), c = ring_point(r_out, z, k + 1, n),
                d = ring_point(r_in, z, k + 1, n);
    out.push_back({a, b, c});
    out.push_back({a, c, d});
  }
  return out;
}

std::vector<Facet> cylinder_side(double r, double z0, double z1, int n) {
  std::vector<Facet> out;
  for (int k = 0; k < n; ++k) {
    const Point a = ring_point(r, z0, k, n), b = ring_point(r, z0, k + 1, n), c = ring_point(r, z1, k + 1, n),
                d = ring_point(r, z1, k, n);
    out.push_back({a, b, c});
    out.push_back({a, c, d});
  }
  return out;
}

// ASCII STL with zero stored normals (accepted by the reader: many exporters write them).
void write_stl(const fs::path& file, const std::vector<Facet>& facets) {
  std::ofstream out(file);
  out << "solid test\n";
  for (const Facet& f : facets) {
    out << "facet normal 0 0 0\nouter loop\n";
    for (const Point& p : f) out << "vertex " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    out << "endloop\nendfacet\n";
  }
  out << "endsolid test\n";
}

struct Folder {
  fs::path path;
  explicit Folder(const std::string& name) : path(fs::path(DEMFIT_BINARY_DIR) / "test_mesh_container" / name) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
};

json lsdyna_case(double frics) {
  return json{{"case", "mesh_container"},
              {"particle", {{"radius", 0.001}, {"density", 2500.0}, {"youngs_modulus", 3e8}, {"poisson_ratio", 0.3}}},
              {"contact",
               {{"normk", 0.01}, {"sheark", 0.05}, {"ndamp", 0.5}, {"tdamp", 0.5}, {"frics", frics}, {"fricr", 0.1}}},
              {"wall_contact", {{"frics", frics}, {"fricd", 0.1}, {"damp", 0.5}}}};
}

// A silo of inner radius 8 mm, 30 mm tall, floor at z = 0 with a centred orifice of diameter 7 mm,
// 150 spheres of radius 1 mm poured in and counted below z = -10 mm.
json silo_case(const fs::path& dir) {
  std::vector<Facet> silo = annulus(3.5, 8.0, 0.0, 32);
  const auto side = cylinder_side(8.0, 0.0, 30.0, 32);
  silo.insert(silo.end(), side.begin(), side.end());
  write_stl(dir / "silo.stl", silo);
  json doc = lsdyna_case(0.3);
  doc["mesh_container"] = {{"meshes", {{{"name", "silo"}, {"stl", "silo.stl"}, {"unit", "mm"}}}},
                           {"fill_box", {{"lower", {-0.0055, -0.0055, 0.002}}, {"upper", {0.0055, 0.0055, 0.03}}}},
                           {"particle_count", 150},
                           {"duration", 0.4},
                           {"output_interval", 0.01},
                           {"outputs", {{"discharge_mass", {{"plane_z", -0.01}, {"orifice_diameter", 0.007}}}}}};
  return doc;
}

std::string parse_error(const json& doc, const fs::path& dir) {
  try {
    parse_case(doc, dir);
  } catch (const std::exception& e) { return e.what(); }
  return "";
}

CaseResult run(const json& doc, const fs::path& dir) {
  return run_case(parse_case(doc, dir), {}, test::test_options());
}

}  // namespace

TEST_CASE("The heap angle definition recovers the angle of a cone of particles on a pedestal") {
  for (const double degrees : {25.0, 35.0}) {
    // 20000 centres uniformly inside a cone of base radius 20 mm on a pedestal top at z = 10 mm.
    const double tan_angle = std::tan(degrees * kPi / 180.0), radius = 0.5e-3, base = 0.01, rc = 0.02;
    std::mt19937_64 engine(7);
    auto uniform = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
    std::vector<std::array<double, 3>> positions;
    while (positions.size() < 20000) {
      const double x = (2 * uniform() - 1) * rc, y = (2 * uniform() - 1) * rc, z = base + uniform() * rc * tan_angle;
      if (std::hypot(x, y) < rc && z <= base + (rc - std::hypot(x, y)) * tan_angle) positions.push_back({x, y, z});
    }
    positions.push_back({0.0, 0.0, base - 0.005});  // a particle below the pedestal top: not the heap
    const std::vector<double> radii(positions.size(), radius);
    HeapAngleSpec heap;
    heap.enabled = true;
    heap.base_z = base;
    heap.r_min = 0.003;
    heap.r_max = 0.017;
    heap.bins = 7;
    CHECK(detail::heap_angle_degrees(positions, radii, heap) == Approx(degrees).margin(1.0));
  }
}

TEST_CASE("The heap angle is undefined when fewer than two annuli of the window hold a particle") {
  HeapAngleSpec heap;
  heap.enabled = true;
  heap.r_min = 0.0;
  heap.r_max = 0.01;
  heap.bins = 5;
  CHECK(std::isnan(detail::heap_angle_degrees({{0.0, 0.0, 0.001}}, {0.001}, heap)));
}

TEST_CASE(
    "Discharged and retained mass add up to the poured mass at every sample, and the silo empties at a Beverloo-order "
    "rate") {
  const Folder folder("silo");
  const CaseResult result = run(silo_case(folder.path), folder.path);
  const double poured = 150 * 2500.0 * 4.0 / 3.0 * kPi * 1e-9;  // N rho 4/3 pi r^3 [kg]
  const CurveTable& history = result.tables.at("history");
  REQUIRE(history.values[0].size() == 40);
  for (std::size_t i = 0; i < history.values[0].size(); ++i)
    CHECK(history.values[1][i] + history.values[2][i] == Approx(poured).epsilon(1e-12));
  const demfit::identify::Curve& discharge = result.curves.at("discharge_mass");
  CHECK(discharge.y_label == "discharged_mass_kg");
  CHECK(discharge.y.front() == 0.0);
  CHECK(discharge.y.back() > 0.5 * poured);
  // Sanity band only: Beverloo's correlation (C 0.58, k 1.5, bulk density 0.6 rho_p) is fitted to
  // large silos; an orifice 3.5 diameters wide and 150 particles may differ by a factor of a few.
  double rate = 0.0, beverloo = 0.0;
  for (const auto& [label, value] : result.summary) {
    if (label.rfind("mean discharge rate", 0) == 0) rate = std::stod(value);
    if (label.rfind("Beverloo reference rate", 0) == 0) beverloo = std::stod(value);
  }
  REQUIRE(beverloo > 0.0);
  CHECK(rate > beverloo / 4.0);
  CHECK(rate < beverloo * 4.0);
}

namespace {

json hertz_case() {
  return json{{"case", "mesh_container"},
              {"particle", {{"radius", 0.001}, {"density", 2500.0}, {"youngs_modulus", 3e8}, {"poisson_ratio", 0.3}}},
              {"contact", {{"law", "hertz_mindlin"}, {"restitution", 0.5}, {"frics", 0.5}, {"fricr", 0.1}}},
              {"wall_contact", {{"youngs_modulus", 3e8}, {"poisson_ratio", 0.3}, {"frics", 0.5}, {"fricr", 0.1}}}};
}

}  // namespace

TEST_CASE("A paddle lifting a sphere that rests on it at lever arm d needs the drive torque m g d, under either law") {
  const bool hertz = GENERATE(false, true);
  CAPTURE(hertz);
  const Folder folder(hertz ? "paddle_hertz" : "paddle");
  // A flat paddle from the axis (the y axis through the origin) out to x = 30 mm, 10 mm wide.
  write_stl(folder.path / "paddle.stl",
            {{Point{0, -5, 0}, Point{30, -5, 0}, Point{30, 5, 0}}, {Point{0, -5, 0}, Point{30, 5, 0}, Point{0, 5, 0}}});
  json doc = hertz ? hertz_case() : lsdyna_case(0.5);
  // Turning right-handed about -y lifts the paddle's +x end: 0.5 rpm tilts it by 0.9 degrees in
  // 0.3 s (cos = 0.99988), too little for the sphere to roll against the rolling friction.
  doc["mesh_container"] = {
      {"meshes",
       {{{"name", "paddle"},
         {"stl", "paddle.stl"},
         {"unit", "mm"},
         {"motion", {{"type", "rotation"}, {"axis_point", {0, 0, 0}}, {"axis_direction", {0, -1, 0}}, {"rpm", 0.5}}}}}},
      {"fill_box", {{"lower", {0.0195, -0.0015, 0.0002}}, {"upper", {0.0225, 0.0015, 0.0032}}}},
      {"particle_count", 1},
      {"duration", 0.3},
      {"output_interval", 0.01},
      {"outputs", {{"moving_part_torque", {{"mesh", "paddle"}}}}}};
  const CaseResult result = run(doc, folder.path);
  const CurveTable& end = result.tables.at("particles_end");
  const double lever = end.values[0].at(0) * 1e-3;  // x of the sphere's centre [m]
  const double weight = 2500.0 * 4.0 / 3.0 * kPi * 1e-9 * 9.81;
  REQUIRE(lever > 0.019);
  const demfit::identify::Curve& torque = result.curves.at("moving_part_torque");
  CHECK(torque.y_label == "torque_Nm");
  CHECK(torque.y.back() == Approx(weight * lever).epsilon(0.01));
}

TEST_CASE("The same mesh_container case run twice gives bit-identical curves") {
  const Folder folder("repeat");
  const json doc = silo_case(folder.path);
  json shorter = doc;
  shorter["mesh_container"]["duration"] = 0.15;
  const CaseResult a = run(shorter, folder.path), b = run(shorter, folder.path);
  REQUIRE(a.curves.at("discharge_mass").y.size() == 15);
  CHECK(a.curves.at("discharge_mass").y.back() > 0.0);  // the flow has begun: the curve is not all zeros
  CHECK(a.curves.at("discharge_mass").y == b.curves.at("discharge_mass").y);
  CHECK(a.tables.at("particles_end").values == b.tables.at("particles_end").values);
}

TEST_CASE("A translating part starts at its start time and carries a sphere resting on it at its velocity") {
  const Folder folder("lift");
  write_stl(folder.path / "plate.stl", {{Point{-15, -15, 0}, Point{15, -15, 0}, Point{15, 15, 0}},
                                        {Point{-15, -15, 0}, Point{15, 15, 0}, Point{-15, 15, 0}}});
  json doc = lsdyna_case(0.5);
  doc["mesh_container"] = {{"meshes",
                            {{{"name", "plate"},
                              {"stl", "plate.stl"},
                              {"unit", "mm"},
                              {"motion", {{"type", "translation"}, {"velocity", {0, 0, 0.01}}, {"start_time", 0.1}}}}}},
                           {"fill_box", {{"lower", {-0.0015, -0.0015, 0.0002}}, {"upper", {0.0015, 0.0015, 0.0032}}}},
                           {"particle_count", 1},
                           {"duration", 0.1},
                           {"output_interval", 0.01},
                           {"outputs", {{"discharge_mass", {{"plane_z", -0.01}}}}}};
  const double resting = run(doc, folder.path).tables.at("particles_end").values[2].at(0);  // z [mm] at 0.1 s
  doc["mesh_container"]["duration"] = 0.3;
  const double lifted = run(doc, folder.path).tables.at("particles_end").values[2].at(0);  // z [mm] at 0.3 s
  // 0.01 m/s for 0.2 s: 2 mm.
  CHECK(lifted - resting == Approx(2.0).epsilon(0.01));
}

TEST_CASE("A size distribution replaces the particle radius and sets the smallest radius of the case") {
  const Folder folder("sizes");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["size_distribution"] = {
      {"unit", "mm"}, {"diameter", {1.5, 2.0}}, {"number_fraction", {0.5, 0.5}}};
  CHECK(
      parse_error(doc, folder.path).find("'particle.radius' cannot be given with 'mesh_container.size_distribution'") ==
      0);
  doc["particle"].erase("radius");
  const CaseSpec spec = parse_case(doc, folder.path);
  CHECK(spec.material.radius == Approx(0.75e-3));
  CHECK(to_json(spec)["mesh_container"]["size_distribution"]["diameter"] == json({1.5, 2.0}));
}

TEST_CASE("A mesh_container case file is a model whose curves are the outputs it selects") {
  const Folder folder("model");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["outputs"]["heap_angle"] = {
      {"center", {0, 0}}, {"base_z", 0.0}, {"r_min", 0.0}, {"r_max", 0.008}};
  std::ofstream(folder.path / "silo.json") << doc.dump(2);
  const auto model = make_model("silo.json", json::object(), folder.path);
  const auto curves = model->curves();
  REQUIRE(curves.size() == 2);
  CHECK(curves[0].name == "heap_angle");
  CHECK(curves[0].y_label == "heap_angle_deg");
  CHECK(curves[1].name == "discharge_mass");
  CHECK(model->default_parameters().count("frics") == 1);
  // The resolved case reads back as the same case.
  CHECK(to_json(parse_case(to_json(parse_case(doc, folder.path)), folder.path)) ==
        to_json(parse_case(doc, folder.path)));
}

TEST_CASE("A missing STL file is refused naming the field and the folder searched") {
  const Folder folder("missing");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["meshes"][0]["stl"] = "nowhere.stl";
  const std::string error = parse_error(doc, folder.path);
  CHECK(error.find("'mesh_container.meshes[0].stl' = \"nowhere.stl\": no such file") != std::string::npos);
  CHECK(error.find("relative to the case file") != std::string::npos);
}

TEST_CASE("An STL part without a unit, or with an unknown one, is refused with the accepted units") {
  const Folder folder("unit");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["meshes"][0].erase("unit");
  CHECK(parse_error(doc, folder.path).find("'mesh_container.meshes[0].unit' is missing: STL files carry no unit") == 0);
  doc["mesh_container"]["meshes"][0]["unit"] = "furlong";
  CHECK(parse_error(doc, folder.path) ==
        "'mesh_container.meshes[0].unit' must be \"m\", \"cm\", \"mm\", \"um\" or \"in\" (got \"furlong\")");
}

TEST_CASE("A rotating part without its axis is refused naming the axis field") {
  const Folder folder("axis");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["meshes"][0]["motion"] = {{"type", "rotation"}, {"rpm", 30}};
  CHECK(parse_error(doc, folder.path)
            .find("'mesh_container.meshes[0].motion.axis_direction' is missing: a rotating part needs its axis") == 0);
}

TEST_CASE("A fill box outside the meshes' extent is refused naming the box and the meshes' range") {
  const Folder folder("box");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["fill_box"]["upper"] = {0.05, 0.0055, 0.03};
  const std::string error = parse_error(doc, folder.path);
  CHECK(error.find("'mesh_container.fill_box' x range") == 0);
  CHECK(error.find("place the box over the geometry") != std::string::npos);
}

TEST_CASE("A negative radius of the heap window is refused naming the field") {
  const Folder folder("radius");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["outputs"]["heap_angle"] = {
      {"center", {0, 0}}, {"base_z", 0.0}, {"r_min", -0.002}, {"r_max", 0.008}};
  CHECK(parse_error(doc, folder.path).find("'mesh_container.outputs.heap_angle.r_min' = -0.002 is a negative radius") ==
        0);
}

TEST_CASE("A torque output on a part that does not rotate is refused") {
  const Folder folder("torque_fixed");
  json doc = silo_case(folder.path);
  doc["mesh_container"]["outputs"]["moving_part_torque"] = {{"mesh", "silo"}};
  CHECK(parse_error(doc, folder.path).find("does not rotate") != std::string::npos);
}
