#pragma once
// STL triangle files (binary and ASCII) for mesh walls. The file carries no unit: the caller
// states the length of one file unit in metres (1e-3 for a file drawn in millimetres).
//
// What is refused, each with a one-line std::runtime_error naming the file and the triangle:
// - a binary file whose size is not 84 + 50 N bytes for the N triangles its header declares
//   (truncated or padded), and an ASCII file that ends inside a facet or has a misspelt keyword;
// - more than StlReadOptions::max_triangles triangles (default 5 million: 250 MB of binary STL,
//   ~0.6 GB of mesh and contact grid), checked from the binary header BEFORE anything is
//   allocated, and while parsing an ASCII file;
// - a coordinate or stored normal that is not a finite number (NaN, infinity);
// - a triangle of zero area (repeated or collinear vertices): it has no normal;
// - an inverted normal: a stored (non-zero) normal pointing against the normal of the vertex
//   winding (right-hand rule, the STL convention). The orientation is refused rather than
//   guessed: contact with a mesh wall is two-sided (triangle_mesh.hpp) and does not use the
//   orientation, but a file whose two orientation records disagree was written wrongly. A zero
//   stored normal (many exporters write one) is accepted.
// Open (non-closed) surfaces are accepted: a drum shell without end caps, an open container.
#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

/// Three vertices [m] in the file's order.
using Triangle = std::array<Vec3, 3>;

struct StlReadOptions {
  double metres_per_unit = 0.0;  ///< length of one file unit [m] (> 0; no default: files have no unit)
  std::size_t max_triangles = 5'000'000;
};

/// Parses STL bytes (binary when the size is 84 + 50 N for the header's N, ASCII when the text
/// starts with "solid"); `name` labels the errors. Vertices are scaled to metres.
std::vector<Triangle> parse_stl(std::string_view bytes, const StlReadOptions& options, const std::string& name);

/// Reads and parses an STL file (refused before reading when larger than the triangle limit allows).
std::vector<Triangle> read_stl(const std::filesystem::path& path, const StlReadOptions& options);

}  // namespace demfit::dem_core
