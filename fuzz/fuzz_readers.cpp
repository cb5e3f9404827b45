// Seeded mutation fuzzer of demfit's input readers: JSON documents (study and case files through
// their strict parsers), curve CSV files, STL meshes (binary and ASCII through
// dem_core::parse_stl, then a TriangleMesh and sphere contacts on it), and drum images (BMP with both header kinds, PNG, JPEG
// through imaging::decode_grey_image, the path read_grey_image takes, then extract_surface).
// Compiled with the project (and with the sanitizers under scripts/sanitize); scripts/fuzz runs it
// for a bounded time. The image seeds are made here, at start-up, from a drawn 40 x 40 px drum.
//
//   fuzz_readers SECONDS [SEED] [OUT_DIR]
//
// Each execution mutates one of the seed inputs (byte flips, inserted JSON/CSV/image tokens, deleted
// and duplicated ranges; a mutated PNG gets its chunk CRCs recomputed half of the time, so that
// mutations reach the decoder and not only the checksum test) and feeds it to the readers. Images
// are read under small limits (1 MiB file, 1024 px a side, 1 megapixel) so that a mutated header
// cannot slow the run down; the limit checks themselves are the same code as for photos.
// A reader may throw std::runtime_error (a clean one-line error) and nothing else: any other
// exception is a finding, saved to OUT_DIR; so is an image read with an inconsistent size or a
// grey level outside [0, 1], or a surface with a non-finite point, or a mesh contact with a
// non-unit normal or an overlap outside (0, r]. A crash (signal or sanitizer
// report) ends the process; OUT_DIR/current.input then holds the input. Prints
// "executions N crashes 0 findings F" at the end, with how many images were read and how many of
// them gave a surface.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "demfit/cases/case_spec.hpp"
#include "demfit/dem_core/stl_mesh.hpp"
#include "demfit/dem_core/triangle_mesh.hpp"
#include "demfit/identify/curve_io.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/imaging/image.hpp"
#include "demfit/imaging/surface.hpp"

namespace {

using namespace std::string_literals;

// A binary STL of two triangles (a corner of a box), zero stored normals.
std::string binary_stl_seed() {
  std::string out(80, 's');
  out.replace(0, 5, "solid");  // a binary header may start like text
  const float t[2][9] = {{0, 0, 0, 2, 0, 0, 0, 2, 0}, {0, 0, 0, 0, 0, 2, 2, 0, 0}};
  auto put = [&](const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); };
  const std::uint32_t count = 2;  // little-endian on the machines this runs on
  put(&count, 4);
  for (const auto& tri : t) {
    const float zero[3] = {0, 0, 0};
    put(zero, 12);
    put(tri, 36);
    out += std::string(2, '\0');
  }
  return out;
}

// Seeds that are not images (the image seeds are made at start-up).
const std::vector<std::string> kTextSeeds = {
    R"({"demfit_study_version": 1, "name": "fuzz", "model": {"case": "analytic", "overrides": {"points": 11},
        "fixed_parameters": {"slope": 0.5}},
        "variables": [{"name": "amplitude", "lower": 0.5, "upper": 2.0, "initial": 1.0},
                      {"name": "rate", "lower": 1.0, "upper": 8.0, "log_scale": true, "initial_range": 0.5}],
        "targets": [{"curve": "response", "name": "t", "x_column": "x_1", "y_column": "y_1",
                     "x": [0, 0.25, 0.5, 1.0], "y": [0, 0.5, 0.8, 1.5], "metric": "mse", "weight": 2}],
        "sampling": {"points_per_iteration": 6, "strategy": "srsm"},
        "domain_reduction": {"gamma_pan": 1.0, "gamma_osc": 0.6, "eta": 0.8},
        "surrogate": {"basis": "gaussian", "responses": "curve_points", "smoothing": 0},
        "stopping": {"max_iterations": 5, "design_tolerance": 0.01, "objective_tolerance": 0.001}, "seed": 3})",
    R"({"case": "pellet_compression", "particle": {"radius": 0.001, "density": 1500},
        "pellet": {"count": 200, "piston_speed": 0.05}, "contact": {"normk": 0.01}})",
    R"({"case": "rotary_drum", "drum": {"coarse_graining": "scg", "scale_factor": 2, "duration": 0.5}})",
    "# comment\nx_1,y_1\n0,0\n0.25,0.5\n0.5,0.8\n1.0,1.5\n",
    "\xEF\xBB\xBFvolume_cm3,pressure_MPa,extra\n\"20.0\",0.0,a\n19.5,+1e-3,b\n19.0,2.5e+00,c\n",
    "solid floor\n facet normal 0 0 1\n  outer loop\n   vertex -1 -1 0\n   vertex 1 -1 0\n   vertex 1 1 0\n"
    "  endloop\n endfacet\n facet normal 0 0 0\n  outer loop\n   vertex -1 -1 0\n   vertex 1 1 0\n"
    "   vertex -1 1 0\n  endloop\n endfacet\nendsolid floor\n",
    binary_stl_seed(),
};

const std::vector<std::string> kTokens = {"[",
                                          "]",
                                          "{",
                                          "}",
                                          "\"",
                                          ",",
                                          ":",
                                          "\n",
                                          "\\",
                                          "\\u0000",
                                          "1e999",
                                          "-0",
                                          "nan",
                                          "null",
                                          "true",
                                          "\"name\":",
                                          "\"x\":[",
                                          "facet normal 0 0 1 outer loop",
                                          "vertex 1e30 0 0",
                                          "endfacet",
                                          "endsolid",
                                          "\xEF\xBB\xBF",
                                          "#",
                                          "\r",
                                          "18446744073709551616",
                                          "-9223372036854775809",
                                          "1e-400",
                                          "\"\":",
                                          "x_1",
                                          "y_1",
                                          ",,,,",
                                          "\x00",
                                          "\xff\xfe",
                                          "[[[[[[[[[[[[",
                                          "]]]]]]]]",
                                          "\xFF\xD9",
                                          "\xFF\xDA\x00\x08"s,
                                          "\xFF\xC0\x00\x11\x08\xFF\xFF"s,
                                          "IEND",
                                          "IDAT",
                                          "\xFF\xFF\xFF\x7F",
                                          "\x00\x00\x01\x00"s,
                                          "\x0C\x00\x00\x00"s,
                                          "BM"};

void put_le(std::string& out, std::uint32_t value, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xFF));
}

// A BMP, bottom-up rows padded to 4 bytes, with the 12-byte OS/2 header (core) or the 40-byte
// Windows header; 24 bits a pixel, or 8 with a 256-entry grey palette (as the GranuDrum photos).
std::string encode_bmp(const demfit::imaging::GreyImage& image, bool core, int bits) {
  const std::uint32_t header = core ? 12 : 40, palette = bits == 8 ? 256 * (core ? 3 : 4) : 0;
  const std::uint32_t offset = 14 + header + palette, bytes = static_cast<std::uint32_t>(bits / 8);
  const std::uint32_t stride = (bytes * image.width + 3) / 4 * 4;
  std::string out = "BM";
  put_le(out, offset + stride * image.height, 4);
  put_le(out, 0, 4);
  put_le(out, offset, 4);
  put_le(out, header, 4);
  put_le(out, image.width, core ? 2 : 4);
  put_le(out, image.height, core ? 2 : 4);
  put_le(out, 1, 2);
  put_le(out, bits, 2);
  if (!core) out.append(24, '\0');
  for (std::uint32_t level = 0; bits == 8 && level < 256; ++level) out.append(core ? 3 : 4, static_cast<char>(level));
  for (int row = image.height - 1; row >= 0; --row) {
    for (int column = 0; column < image.width; ++column)
      out.append(bytes, static_cast<char>(static_cast<unsigned char>(
                            255.0f * image.value[static_cast<std::size_t>(row) * image.width + column])));
    out.append(stride - bytes * image.width, '\0');
  }
  return out;
}

// A progressive JPEG (T.81 annex G) written byte by byte, as stb_image_write has no progressive
// mode: 16 x 16 px, one component, one DC-only first scan in which every block's DC difference is
// 0 (category 0, the only code of a one-entry Huffman table, "0"), so it decodes to flat grey 128.
// It seeds stb_image's progressive decoder for the mutations.
std::string progressive_jpeg() {
  std::string jpeg = "\xFF\xD8"s;
  jpeg += "\xFF\xDB\x00\x43\x00"s + std::string(64, '\x01');                // quantisation table 0: all 1
  jpeg += "\xFF\xC2\x00\x0B\x08\x00\x10\x00\x10\x01\x01\x11\x00"s;          // SOF2: 16 x 16, 1 component
  jpeg += "\xFF\xC4\x00\x14\x00\x01"s + std::string(15, '\x00') + "\x00"s;  // DC table 0: one 1-bit code
  jpeg += "\xFF\xDA\x00\x08\x01\x01\x00\x00\x00\x00"s;                      // SOS: DC first scan
  jpeg += "\x0F\xFF\xD9"s;  // four blocks coded "0", padded with 1 bits; End Of Image
  return jpeg;
}

// The seeds: the text documents above and a 40 x 40 px drum (dark bed below the line z = -0.4 x,
// light above) as BMP (both headers, 24-bit and 8-bit paletted), PNG and JPEG, and a
// progressive JPEG.
std::vector<std::string> make_seeds() {
  using namespace demfit::imaging;
  GreyImage drum;
  drum.width = drum.height = 40;
  for (int row = 0; row < 40; ++row)
    for (int column = 0; column < 40; ++column) {
      const double x = pixel_x(column, 40, 0.084), z = pixel_z(row, 40, 0.084);
      drum.value.push_back(z < -0.4 * x ? 0.1f : 0.9f);
    }
  std::vector<std::string> seeds = kTextSeeds;
  for (const bool core : {true, false})
    for (const int bits : {24, 8}) seeds.push_back(encode_bmp(drum, core, bits));
  seeds.push_back(encode_png(to_rgb(drum)));
  seeds.push_back(encode_jpeg(to_rgb(drum), 75));
  seeds.push_back(progressive_jpeg());
  return seeds;
}

// Rewrites the CRC of every whole chunk of a PNG (after its 8-byte signature).
void fix_png_crcs(std::string& png) {
  std::size_t at = 8;
  while (at + 12 <= png.size()) {
    std::uint32_t length = 0;
    for (int k = 0; k < 4; ++k) length = (length << 8) | static_cast<unsigned char>(png[at + k]);
    if (length > png.size() || at + 12 + length > png.size()) return;
    const std::uint32_t crc = demfit::imaging::png_crc32(std::string_view(png).substr(at + 4, 4 + length));
    for (int k = 0; k < 4; ++k) png[at + 8 + length + k] = static_cast<char>((crc >> (8 * (3 - k))) & 0xFF);
    at += 12 + length;
  }
}

std::string mutate(std::string text, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % n); };
  const int steps = 1 + static_cast<int>(rng() % 8);
  for (int s = 0; s < steps; ++s) {
    const std::size_t at = pick(text.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (!text.empty()) text[pick(text.size())] ^= static_cast<char>(1u << (rng() % 8));
        break;
      case 1:
        text.insert(at, kTokens[pick(kTokens.size())]);
        break;
      case 2:
        text.erase(at, pick(16));
        break;
      case 3: {
        const std::size_t from = pick(text.size() + 1);
        text.insert(at, text.substr(from, pick(64)));
        break;
      }
      case 4:
        text.insert(at, 1, static_cast<char>(rng() & 0xff));
        break;
      default:
        if (!text.empty()) text.resize(pick(text.size()));
        break;
    }
  }
  if (text.size() > (1u << 16)) text.resize(1u << 16);
  if (text.compare(0, 4, "\x89PNG") == 0 && rng() % 2 == 0) fix_png_crcs(text);
  return text;
}

// Executions in which the image reader returned a picture, and the extraction a surface.
long images_read = 0, surfaces_found = 0;

// The image reader, then the surface extraction on what it read. Returns "" or what went wrong
// other than a one-line refusal.
std::string execute_image(const std::string& bytes) {
  using namespace demfit::imaging;
  const ImageLimits limits{std::uintmax_t{1} << 20, 1024, 1 << 20};
  try {
    const GreyImage image = decode_grey_image(bytes, "fuzz image", limits);
    ++images_read;
    if (image.width <= 0 || image.height <= 0 || image.width > limits.side || image.height > limits.side ||
        image.value.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
      return "image read with inconsistent size " + std::to_string(image.width) + " x " + std::to_string(image.height);
    for (const float v : image.value)
      if (!(v >= 0.0f && v <= 1.0f)) return "image read with a grey level outside [0, 1]";
    try {
      const SurfaceProfile profile = extract_surface(image, DrumFrame{0.084}, ProfileOptions{});
      ++surfaces_found;
      for (std::size_t i = 0; i < profile.x.size(); ++i)
        if (!std::isfinite(profile.x[i]) || !std::isfinite(profile.z[i])) return "surface with a non-finite point";
    } catch (const std::runtime_error&) {}
  } catch (const std::runtime_error&) {}
  return {};
}

// Executions in which the STL reader returned a mesh.
long meshes_built = 0;

// The STL reader, then a mesh and a few sphere contacts on what it read.
std::string execute_stl(const std::string& bytes) {
  using namespace demfit::dem_core;
  try {
    const TriangleMesh mesh(parse_stl(bytes, {1e-3, 1000}, "fuzz.stl"));
    ++meshes_built;
    const Vec3 lo = mesh.lower(), hi = mesh.upper(), mid = 0.5 * (lo + hi);
    const double radius = 0.25 * norm(hi - lo) + 1e-6;
    for (const Vec3& c : {lo, hi, mid, Vec3{lo.x, mid.y, hi.z}}) {
      MeshContact found[4];
      const int n = mesh.contacts(c, radius, found, 4);
      for (int k = 0; k < n; ++k)
        if (!(std::abs(norm(found[k].normal) - 1.0) < 1e-9) || !(found[k].overlap > 0.0 && found[k].overlap <= radius))
          return "mesh contact with a non-unit normal or an overlap outside (0, r]";
    }
  } catch (const std::runtime_error&) {}
  return {};
}

// One execution: every reader on the text. Returns "" or the name of an unexpected exception.
std::string execute(const std::string& text) {
  try {
    try {
      const nlohmann::json json = demfit::identify::parse_json_document(text, "fuzz input");
      try {
        demfit::identify::parse_study(json, "/nonexistent-fuzz-folder");
      } catch (const std::runtime_error&) {}
      try {
        demfit::cases::parse_case(json);
      } catch (const std::runtime_error&) {}
    } catch (const std::runtime_error&) {}
    try {
      std::istringstream in(text);
      demfit::identify::parse_curve_csv(in, "fuzz.csv", "x_1", "y_1");
    } catch (const std::runtime_error&) {}
    if (const std::string problem = execute_stl(text); !problem.empty()) return problem;
    if (const std::string problem = execute_image(text); !problem.empty()) return problem;
  } catch (const std::exception& e) { return std::string("unexpected exception: ") + e.what(); }
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuzz_readers SECONDS [SEED] [OUT_DIR]\n");
    return 2;
  }
  const double seconds = std::stod(argv[1]);
  const std::uint64_t seed = argc > 2 ? std::stoull(argv[2]) : 1;
  const std::filesystem::path out = argc > 3 ? argv[3] : "fuzz-findings";
  std::filesystem::create_directories(out);
  const int current = ::open((out / "current.input").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const std::vector<std::string> seeds = make_seeds();
  for (std::size_t k = kTextSeeds.size(); k < seeds.size(); ++k) {  // unmutated, every image seed reads
    try {
      demfit::imaging::decode_grey_image(seeds[k], "image seed " + std::to_string(k));
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 2;
    }
  }
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  long executions = 0, findings = 0;
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds) {
    for (int batch = 0; batch < 64; ++batch) {
      const std::string input = mutate(seeds[rng() % seeds.size()], rng);
      if (current >= 0 && ::ftruncate(current, 0) == 0)
        if (::pwrite(current, input.data(), input.size(), 0) < 0) return 3;
      const std::string problem = execute(input);
      ++executions;
      if (!problem.empty()) {
        ++findings;
        std::ofstream(out / ("finding-" + std::to_string(findings) + ".input"), std::ios::binary) << input;
        std::fprintf(stderr, "finding %ld: %s\n", findings, problem.substr(0, 200).c_str());
      }
    }
  }
  if (current >= 0) ::close(current);
  std::filesystem::remove(out / "current.input");
  std::printf(
      "executions %ld crashes 0 findings %ld (seed %llu, %.0f s; images read %ld, surfaces found %ld, STL meshes "
      "built %ld)\n",
      executions, findings, static_cast<unsigned long long>(seed), seconds, images_read, surfaces_found, meshes_built);
  return findings == 0 ? 0 : 1;
}
