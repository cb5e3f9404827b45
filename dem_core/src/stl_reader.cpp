// STL reader (binary and ASCII) for mesh walls; the format: 80-byte header, uint32 triangle count,
// then per triangle 12 little-endian float32 (normal, three vertices) and a uint16 attribute; or
// the text form "solid ... facet normal n n n outer loop vertex x y z (x3) endloop endfacet ...
// endsolid". Rules and refusals: stl_mesh.hpp.
#include "demfit/dem_core/stl_mesh.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace demfit::dem_core {
namespace {

constexpr std::size_t kHeaderBytes = 84, kFacetBytes = 50;

[[noreturn]] void refuse(const std::string& name, const std::string& what) {
  throw std::runtime_error("STL '" + name + "': " + what);
}

/// Scales and checks one facet (finite, non-zero area, stored normal not against the winding).
Triangle checked_facet(const Vec3& stored_normal, const Triangle& raw, std::size_t index, double scale,
                       const std::string& name) {
  const std::string where = "triangle " + std::to_string(index) + ": ";
  for (const Vec3& v : raw)
    if (!is_finite(v)) refuse(name, where + "a vertex coordinate is not a finite number (NaN or infinity); fix the file");
  if (!is_finite(stored_normal)) refuse(name, where + "the stored normal is not a finite number; fix the file");
  const Triangle t{raw[0] * scale, raw[1] * scale, raw[2] * scale};
  for (const Vec3& v : t)
    if (!is_finite(v)) refuse(name, where + "a vertex overflows when scaled to metres; check metres_per_unit");
  const Vec3 winding = cross(t[1] - t[0], t[2] - t[0]);
  if (norm2(winding) == 0.0)
    refuse(name, where + "zero area (repeated or collinear vertices); remove the triangle from the file");
  if (dot(winding, stored_normal) < 0.0)
    refuse(name, where + "inverted normal: the stored normal points against the vertex winding (right-hand rule); "
                         "re-export the file with consistent orientation");
  return t;
}

float read_float(const char* p) {
  std::uint32_t bits = 0;
  for (int b = 3; b >= 0; --b) bits = (bits << 8) | static_cast<unsigned char>(p[b]);  // little-endian
  float f = 0.0f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

Vec3 read_vec(const char* p) { return {read_float(p), read_float(p + 4), read_float(p + 8)}; }

std::uint32_t declared_count(std::string_view bytes) {
  std::uint32_t n = 0;
  for (int b = 3; b >= 0; --b) n = (n << 8) | static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(b)]);
  return n;
}

std::vector<Triangle> parse_binary(std::string_view bytes, const StlReadOptions& o, const std::string& name) {
  const std::uint64_t n = declared_count(bytes);
  if (n > o.max_triangles)
    refuse(name, "the header declares " + std::to_string(n) + " triangles, above the limit of " +
                     std::to_string(o.max_triangles) + "; coarsen the mesh");
  if (n == 0) refuse(name, "the header declares 0 triangles; a mesh wall needs at least one");
  if (bytes.size() != kHeaderBytes + kFacetBytes * n)
    refuse(name, "binary header declares " + std::to_string(n) + " triangles (" +
                     std::to_string(kHeaderBytes + kFacetBytes * n) + " bytes) but the file has " +
                     std::to_string(bytes.size()) + " bytes: truncated or not an STL file");
  std::vector<Triangle> out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const char* f = bytes.data() + kHeaderBytes + kFacetBytes * k;
    out.push_back(checked_facet(read_vec(f), {read_vec(f + 12), read_vec(f + 24), read_vec(f + 36)}, k,
                                o.metres_per_unit, name));
  }
  return out;
}

/// Whitespace-separated tokens of the ASCII form.
struct Tokens {
  std::string_view text;
  std::size_t at = 0;
  std::string_view next() {
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; };
    while (at < text.size() && space(text[at])) ++at;
    const std::size_t begin = at;
    while (at < text.size() && !space(text[at])) ++at;
    return text.substr(begin, at - begin);
  }
};

void expect(Tokens& in, std::string_view word, std::size_t facet, const std::string& name) {
  const std::string_view got = in.next();
  if (got != word)
    refuse(name, "facet " + std::to_string(facet) + ": expected '" + std::string(word) + "', found '" +
                     std::string(got.empty() ? "end of file" : got.substr(0, 40)) + "' (malformed or truncated ASCII STL)");
}

double number(Tokens& in, std::size_t facet, const std::string& name) {
  const std::string_view t = in.next();
  double v = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc{} || end != t.data() + t.size())
    refuse(name, "facet " + std::to_string(facet) + ": '" + std::string(t.empty() ? "end of file" : t.substr(0, 40)) +
                     "' is not a number (malformed or truncated ASCII STL)");
  return v;
}

Vec3 vec(Tokens& in, std::size_t facet, const std::string& name) {
  const double x = number(in, facet, name), y = number(in, facet, name);
  return {x, y, number(in, facet, name)};
}

std::vector<Triangle> parse_ascii(std::string_view text, const StlReadOptions& o, const std::string& name) {
  Tokens in{text};
  in.next();  // "solid"
  const std::size_t name_end = text.find('\n', in.at);
  in.at = name_end == std::string_view::npos ? text.size() : name_end;  // the solid's name: rest of the line
  std::vector<Triangle> out;
  for (;;) {
    const std::string_view word = in.next();
    if (word == "endsolid") break;
    if (word != "facet")
      refuse(name, "after facet " + std::to_string(out.size()) + ": expected 'facet' or 'endsolid', found '" +
                       std::string(word.empty() ? "end of file" : word.substr(0, 40)) + "' (malformed or truncated ASCII STL)");
    if (out.size() == o.max_triangles)
      refuse(name, "more than " + std::to_string(o.max_triangles) + " triangles (the limit); coarsen the mesh");
    const std::size_t k = out.size();
    expect(in, "normal", k, name);
    const Vec3 normal = vec(in, k, name);
    expect(in, "outer", k, name);
    expect(in, "loop", k, name);
    Triangle raw;
    for (Vec3& v : raw) {
      expect(in, "vertex", k, name);
      v = vec(in, k, name);
    }
    expect(in, "endloop", k, name);
    expect(in, "endfacet", k, name);
    out.push_back(checked_facet(normal, raw, k, o.metres_per_unit, name));
  }
  if (out.empty()) refuse(name, "no facets; a mesh wall needs at least one triangle");
  return out;
}

bool starts_with_solid(std::string_view bytes) {
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && bytes.substr(first, 5) == "solid";
}

}  // namespace

std::vector<Triangle> parse_stl(std::string_view bytes, const StlReadOptions& options, const std::string& name) {
  if (!std::isfinite(options.metres_per_unit) || options.metres_per_unit <= 0.0)
    refuse(name, "metres_per_unit must be a finite length > 0 [m per file unit] (1e-3 for a file in millimetres)");
  const bool binary_size_matches =
      bytes.size() >= kHeaderBytes && bytes.size() == kHeaderBytes + kFacetBytes * std::uint64_t{declared_count(bytes)};
  // A binary header may begin with "solid" too: text never holds a NUL byte.
  const bool text = starts_with_solid(bytes) && bytes.find('\0') == std::string_view::npos;
  if (binary_size_matches || (!text && bytes.size() >= kHeaderBytes)) return parse_binary(bytes, options, name);
  if (text) return parse_ascii(bytes, options, name);
  refuse(name, std::to_string(bytes.size()) +
                   " bytes: shorter than a binary STL header (84 bytes) and not ASCII STL (no leading 'solid')");
}

std::vector<Triangle> read_stl(const std::filesystem::path& path, const StlReadOptions& options) {
  const std::string name = path.string();
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) refuse(name, "cannot read the file (" + ec.message() + ")");
  // ASCII facets take ~250 bytes; 1 KB per triangle bounds both forms before anything is read.
  if (size > 1024 + 1024 * std::uintmax_t{options.max_triangles})
    refuse(name, std::to_string(size) + " bytes: too large for the limit of " + std::to_string(options.max_triangles) +
                     " triangles; coarsen the mesh");
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) refuse(name, "cannot read the file");
  return parse_stl(bytes, options, name);
}

}  // namespace demfit::dem_core
