// STL reader: binary and ASCII give the same triangles in metres; malformed, truncated, NaN,
// inverted-normal, zero-area and oversized files are refused with a one-line error.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "demfit/dem_core/stl_mesh.hpp"
#include "mesh_shapes.hpp"

using namespace demfit::dem_core;

namespace {

void put_u32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xFFu));
}
void put_float(std::string& out, float f) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof f);
  put_u32(out, bits);
}
void put_vec(std::string& out, const Vec3& v) {
  put_float(out, static_cast<float>(v.x));
  put_float(out, static_cast<float>(v.y));
  put_float(out, static_cast<float>(v.z));
}

Vec3 winding_normal(const Triangle& t) { return cross(t[1] - t[0], t[2] - t[0]); }

std::string binary_stl(const std::vector<Triangle>& ts, double normal_sign = 1.0) {
  std::string out(80, ' ');
  put_u32(out, static_cast<std::uint32_t>(ts.size()));
  for (const Triangle& t : ts) {
    put_vec(out, normal_sign * winding_normal(t));
    for (const Vec3& v : t) put_vec(out, v);
    out += std::string(2, '\0');
  }
  return out;
}

std::string ascii_stl(const std::vector<Triangle>& ts, const std::string& x_of_first = "") {
  std::ostringstream out;
  out.precision(9);
  out << "solid test box\n";
  for (std::size_t k = 0; k < ts.size(); ++k) {
    const Vec3 n = winding_normal(ts[k]);
    out << "  facet normal " << n.x << ' ' << n.y << ' ' << n.z << "\n    outer loop\n";
    for (const Vec3& v : ts[k])
      out << "      vertex " << (k == 0 && !x_of_first.empty() ? x_of_first : std::to_string(v.x)) << ' ' << v.y << ' '
          << v.z << "\n";
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid test box\n";
  return out.str();
}

/// The error message of parsing `bytes`, "" when it parses.
std::string stl_parse_error(const std::string& bytes, std::size_t max_triangles = 5'000'000) {
  try {
    parse_stl(bytes, {1e-3, max_triangles}, "case.stl");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// A box in millimetres with coordinates exact in float and in decimal.
const std::vector<Triangle> box_mm = demfit::dem_core::test::box_triangles({-25, -10, 0}, {25, 10, 40});

}  // namespace

TEST_CASE("Binary and ASCII STL files of the same box give the same triangles, scaled to metres", "[dem_core][stl]") {
  const auto from_binary = parse_stl(binary_stl(box_mm), {1e-3}, "box.stl");
  const auto from_ascii = parse_stl(ascii_stl(box_mm), {1e-3}, "box.stl");
  REQUIRE(from_binary.size() == 12);
  REQUIRE(from_ascii.size() == 12);
  for (std::size_t k = 0; k < 12; ++k)
    for (std::size_t v = 0; v < 3; ++v) {
      CHECK(from_binary[k][v] == from_ascii[k][v]);
      CHECK(from_binary[k][v] == 1e-3 * box_mm[k][v]);
    }
  // A file on disk reads the same; a closed box welds to 8 vertices.
  const auto path = std::filesystem::temp_directory_path() / "demfit_test_stl_reader_box.stl";
  {
    std::ofstream out(path, std::ios::binary);
    out << binary_stl(box_mm);
  }
  const auto from_file = read_stl(path, {1e-3});
  std::filesystem::remove(path);
  CHECK(from_file == from_binary);
  CHECK(TriangleMesh(from_file).vertex_count() == 8);
}

TEST_CASE("A truncated binary STL is refused, naming the declared and actual sizes", "[dem_core][stl]") {
  const std::string whole = binary_stl(box_mm);
  const std::string message = stl_parse_error(whole.substr(0, whole.size() - 10));
  CHECK(message.find("truncated") != std::string::npos);
  CHECK(message.find("12 triangles") != std::string::npos);
  CHECK(stl_parse_error(whole.substr(0, 40)).find("shorter than a binary STL header") != std::string::npos);
}

TEST_CASE("A truncated or misspelt ASCII STL is refused, naming the facet", "[dem_core][stl]") {
  const std::string whole = ascii_stl(box_mm);
  CHECK(stl_parse_error(whole.substr(0, whole.size() / 2)).find("malformed or truncated ASCII STL") !=
        std::string::npos);
  std::string misspelt = whole;
  misspelt.replace(misspelt.find("outer loop"), 10, "outer lop ");
  const std::string message = stl_parse_error(misspelt);
  CHECK(message.find("facet 0: expected 'loop'") != std::string::npos);
  CHECK(message.find('\n') == std::string::npos);  // one line
}

TEST_CASE("NaN coordinates are refused in both STL forms", "[dem_core][stl]") {
  CHECK(stl_parse_error(ascii_stl(box_mm, "nan")).find("triangle 0: a vertex coordinate is not a finite number") !=
        std::string::npos);
  auto broken = box_mm;
  broken[3][1].y = std::numeric_limits<double>::quiet_NaN();
  CHECK(stl_parse_error(binary_stl(broken)).find("triangle 3: a vertex coordinate is not a finite number") !=
        std::string::npos);
}

TEST_CASE("An STL normal pointing against the vertex winding is refused; a zero normal is accepted",
          "[dem_core][stl]") {
  CHECK(stl_parse_error(binary_stl(box_mm, -1.0)).find("triangle 0: inverted normal") != std::string::npos);
  CHECK(stl_parse_error(binary_stl(box_mm, 0.0)).empty());
}

TEST_CASE("A zero-area STL triangle is refused", "[dem_core][stl]") {
  auto broken = box_mm;
  broken[5][2] = broken[5][0];
  CHECK(stl_parse_error(binary_stl(broken, 0.0)).find("triangle 5: zero area") != std::string::npos);
}

TEST_CASE("An STL above the triangle limit is refused from its header, before allocating", "[dem_core][stl]") {
  std::string header(80, ' ');
  put_u32(header, 10'000'000);  // claims 10 million triangles (500 MB) in an 84-byte file
  const std::string message = stl_parse_error(header);
  CHECK(message.find("declares 10000000 triangles, above the limit of 5000000") != std::string::npos);
  CHECK(stl_parse_error(ascii_stl(box_mm), 11).find("more than 11 triangles") != std::string::npos);
}

TEST_CASE("An STL without a stated positive unit is refused", "[dem_core][stl]") {
  CHECK_THROWS_WITH(parse_stl(binary_stl(box_mm), {0.0}, "box.stl"), Catch::Contains("metres_per_unit"));
}
