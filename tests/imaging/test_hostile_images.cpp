// Hostile image files: decompression bombs are refused from their header or stopped by the decoding
// budget, corrupted PNG chunks and truncated BMPs (every header variant) are refused rather than
// read as zeros, OS/2 palettes are read whole, phone trailers after a JPEG's End Of Image and stray
// bytes between its segments are ignored, pictures that are not drum photos (noise,
// checkerboards) give no surface, and drum diameters outside 1 mm .. 100 m are refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "demfit/imaging/image.hpp"
#include "demfit/imaging/occupancy.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "demfit/imaging/surface.hpp"
#include "drawn_images.hpp"

using namespace demfit::imaging;
namespace fs = std::filesystem;

namespace {

fs::path hostile_images_scratch(const std::string& name) {
  const fs::path dir = fs::path(DEMFIT_BINARY_DIR) / "test_hostile_images_scratch" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using test::write_bytes;

void put_le(std::string& out, std::uint32_t value, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xFF));
}

void put_be(std::string& out, std::uint32_t value, int bytes) {
  for (int k = bytes - 1; k >= 0; --k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xFF));
}

// CRC-32 bit by bit (PNG specification annex D), independent of the table-driven reader's.
std::uint32_t crc32_bitwise(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const char b : bytes) {
    c ^= static_cast<unsigned char>(b);
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::string png_chunk(const std::string& type, const std::string& data) {
  std::string chunk;
  put_be(chunk, static_cast<std::uint32_t>(data.size()), 4);
  chunk += type + data;
  put_be(chunk, crc32_bitwise(type + data), 4);
  return chunk;
}

// A PNG with valid checksums: 8-bit grey IHDR of the given size, one IDAT holding `zlib`, IEND.
std::string grey_png(std::uint32_t width, std::uint32_t height, const std::string& zlib) {
  std::string ihdr;
  put_be(ihdr, width, 4);
  put_be(ihdr, height, 4);
  ihdr += std::string("\x08\x00\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1A\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", zlib) +
         png_chunk("IEND", "");
}

// A zlib stream (RFC 1950/1951) inflating to `count` x 258 zero bytes: one literal 0, then
// back-references of length 258 at distance 1 in a fixed-Huffman block (13 bits per 258 bytes).
std::string zero_bomb(std::uint32_t count) {
  std::string out("\x78\x01", 2);
  std::uint32_t buffer = 0;
  int used = 0;
  auto bits_lsb = [&](std::uint32_t value, int n) {  // header fields: least significant bit first
    for (int k = 0; k < n; ++k) {
      buffer |= ((value >> k) & 1u) << used;
      if (++used == 8) out.push_back(static_cast<char>(buffer)), buffer = 0, used = 0;
    }
  };
  auto code = [&](std::uint32_t value, int n) {  // Huffman codes: most significant bit first
    for (int k = n - 1; k >= 0; --k) bits_lsb((value >> k) & 1u, 1);
  };
  bits_lsb(1, 1);  // BFINAL
  bits_lsb(1, 2);  // BTYPE = fixed Huffman
  code(0x30, 8);   // literal 0
  for (std::uint32_t k = 0; k + 1 < count; ++k) {
    code(0xC5, 8);  // length symbol 285 = 258 bytes
    code(0x00, 5);  // distance symbol 0 = 1 byte back
  }
  code(0x00, 7);  // end of block
  if (used > 0) out.push_back(static_cast<char>(buffer));
  const std::uint64_t total = 1 + 258ull * (count - 1);
  put_be(out, static_cast<std::uint32_t>((total % 65521) << 16 | 1u), 4);  // Adler-32 of zeros
  return out;
}

// A 24-bit BMP of `image`, bottom-up rows padded to 4 bytes, with the 12-byte OS/2
// BITMAPCOREHEADER (core = true) or the 40-byte BITMAPINFOHEADER.
std::string encode_bmp(const GreyImage& image, bool core) {
  const std::uint32_t header = core ? 12 : 40, offset = 14 + header;
  const std::uint32_t stride = (3 * image.width + 3) / 4 * 4, data = stride * image.height;
  std::string out = "BM";
  put_le(out, offset + data, 4);
  put_le(out, 0, 4);
  put_le(out, offset, 4);
  put_le(out, header, 4);
  put_le(out, image.width, core ? 2 : 4);
  put_le(out, image.height, core ? 2 : 4);
  put_le(out, 1, 2);
  put_le(out, 24, 2);
  if (!core) out.append(24, '\0');  // no compression, sizes and palette counts left 0
  for (int row = image.height - 1; row >= 0; --row) {
    for (int column = 0; column < image.width; ++column)
      out.append(3, static_cast<char>(
                        std::lround(255.0f * image.value[static_cast<std::size_t>(row) * image.width + column])));
    out.append(stride - 3 * image.width, '\0');
  }
  return out;
}

GreyImage small_drum() {
  test::DrawnDrum drum;
  drum.pixels = 64;
  return test::draw_surface(drum, [](double x) { return -0.5 * x; });
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("BMP, PNG and JPEG headers declaring far more pixels than the limit are refused before decoding") {
  const fs::path dir = hostile_images_scratch("declared");
  std::string bmp = "BM";  // 100000 x 100000 x 24 bits would be 30 GB of pixels; 126 bytes here
  put_le(bmp, 126, 4);
  put_le(bmp, 0, 4);
  put_le(bmp, 54, 4);
  put_le(bmp, 40, 4);
  put_le(bmp, 100000, 4);
  put_le(bmp, 100000, 4);
  put_le(bmp, 1, 2);
  put_le(bmp, 24, 2);
  bmp.resize(126, '\0');
  write_bytes(dir / "bomb.bmp", bmp);
  write_bytes(dir / "bomb.png", grey_png(100000, 100000, zero_bomb(4)));
  // An iPhone-optimised PNG puts an Apple CgBI chunk before IHDR; its IHDR is read all the same.
  std::string cgbi = grey_png(100000, 100000, zero_bomb(4));
  cgbi.insert(8, png_chunk("CgBI", std::string("\x50\x00\x20\x02", 4)));
  write_bytes(dir / "bomb_cgbi.png", cgbi);
  // JPEG sizes are 16-bit: the largest, 65535 x 65535, patched into a valid JPEG's frame header.
  std::string jpeg = encode_jpeg(to_rgb(small_drum()), 90);
  const std::size_t frame = jpeg.find("\xFF\xC0");
  REQUIRE(frame != std::string::npos);
  jpeg.replace(frame + 5, 4, "\xFF\xFF\xFF\xFF");
  write_bytes(dir / "bomb.jpg", jpeg);
  for (const auto& [file, declared] :
       {std::pair{"bomb.bmp", "100000 x 100000"}, std::pair{"bomb.png", "100000 x 100000"},
        std::pair{"bomb_cgbi.png", "100000 x 100000"}, std::pair{"bomb.jpg", "65535 x 65535"}}) {
    const auto start = std::chrono::steady_clock::now();
    CHECK_THROWS_WITH(read_grey_image(dir / file), Catch::Contains(file) && Catch::Contains(declared) &&
                                                       Catch::Contains("50 megapixels") &&
                                                       Catch::Contains("20000 pixels a side"));
    CHECK(seconds_since(start) < 0.2);
  }
}

TEST_CASE("a PNG whose compressed data inflates far beyond its declared size is stopped by the decoding budget") {
  const fs::path dir = hostile_images_scratch("inflate");
  // 100 x 100 pixels need 10 100 inflated bytes; this 1.3 MB stream inflates to 258 MB.
  write_bytes(dir / "inflate.png", grey_png(100, 100, zero_bomb(1000000)));
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(read_grey_image(dir / "inflate.png"),
                    Catch::Contains("inflate.png") && Catch::Contains("MiB to decode"));
  CHECK(seconds_since(start) < 1.0);
}

TEST_CASE("a PNG with one flipped byte in a chunk is refused, naming the chunk") {
  const fs::path dir = hostile_images_scratch("crc");
  const std::string png = encode_png(to_rgb(small_drum()));
  write_bytes(dir / "whole.png", png);
  CHECK(read_grey_image(dir / "whole.png").width == 64);
  for (const std::string type : {"IHDR", "IDAT", "IEND"}) {
    std::string flipped = png;
    const std::size_t at = flipped.find(type);
    REQUIRE(at != std::string::npos);
    flipped[at + (type == "IEND" ? 5 : 6)] ^= 0x10;  // IEND has no data: flip its stored CRC
    write_bytes(dir / "flipped.png", flipped);
    CHECK_THROWS_WITH(read_grey_image(dir / "flipped.png"),
                      Catch::Contains("flipped.png") && Catch::Contains("'" + type + "'") && Catch::Contains("CRC"));
  }
}

TEST_CASE("a BMP is refused as truncated when it holds one row less than its header declares, for both header kinds") {
  const fs::path dir = hostile_images_scratch("bmp_rows");
  const GreyImage drawn = small_drum();
  for (const bool core : {true, false}) {
    const std::string bmp = encode_bmp(drawn, core);
    write_bytes(dir / "whole.bmp", bmp);
    const GreyImage read = read_grey_image(dir / "whole.bmp");
    REQUIRE(read.width == 64);
    double worst = 0.0;
    for (std::size_t k = 0; k < read.value.size(); ++k)
      worst = std::max(worst, std::abs(static_cast<double>(read.value[k] - drawn.value[k])));
    CHECK(worst <= 0.5 / 255.0 + 1e-6);  // every row read, rows bottom-up, to 8-bit rounding
    const std::size_t stride = (3 * 64 + 3) / 4 * 4;
    write_bytes(dir / "row_short.bmp", bmp.substr(0, bmp.size() - stride));
    CHECK_THROWS_WITH(read_grey_image(dir / "row_short.bmp"),
                      Catch::Contains("row_short.bmp") && Catch::Contains("truncated"));
    write_bytes(dir / "byte_short.bmp", bmp.substr(0, bmp.size() - 1));
    CHECK_THROWS_WITH(read_grey_image(dir / "byte_short.bmp"), Catch::Contains("truncated"));
  }
}

TEST_CASE("a JPEG followed by a 4 KiB phone trailer decodes to the same pixels as without it") {
  const fs::path dir = hostile_images_scratch("trailer");
  const std::string jpeg = encode_jpeg(to_rgb(small_drum()), 90);
  // Trailer bytes as phones append them (metadata blocks, an embedded preview): random bytes that
  // include Start Of Image, End Of Image and Start Of Scan markers.
  std::mt19937 rng(7);
  std::string trailer = "SEFH";
  while (trailer.size() < 4096) trailer.push_back(static_cast<char>(rng() & 0xFF));
  for (std::size_t at : {100u, 900u, 2000u}) trailer.replace(at, 4, "\xFF\xD8\xFF\xD9");
  trailer.replace(3000, 4, std::string("\xFF\xDA\x00\x08", 4));
  write_bytes(dir / "plain.jpg", jpeg);
  write_bytes(dir / "trailer.jpg", jpeg + trailer);
  const GreyImage plain = read_grey_image(dir / "plain.jpg");
  const GreyImage trailed = read_grey_image(dir / "trailer.jpg");
  REQUIRE(trailed.width == plain.width);
  REQUIRE(trailed.height == plain.height);
  CHECK(trailed.value == plain.value);
  // Without its End Of Image marker the same bytes are still refused as truncated.
  write_bytes(dir / "cut.jpg", jpeg.substr(0, jpeg.size() - 2) + std::string(4096, '\0'));
  CHECK_THROWS_WITH(read_grey_image(dir / "cut.jpg"), Catch::Contains("cut.jpg") && Catch::Contains("truncated"));
}

TEST_CASE("random noise and checkerboards are refused as drum photos while drawn drums are accepted") {
  constexpr int kPixels = 406;
  auto picture = [](const std::string& name, const std::function<float(int, int)>& grey) {
    GreyImage image;
    image.width = image.height = kPixels;
    image.source = name;
    for (int row = 0; row < kPixels; ++row)
      for (int column = 0; column < kPixels; ++column) image.value.push_back(grey(row, column));
    return image;
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const std::vector<GreyImage> hostile = {
      picture("uniform_noise.png", [&](int, int) { return uniform(rng); }),
      // Two grey levels, 70 % dark: the dark pixels percolate into one cluster touching the bottom.
      picture("dense_speckle.png", [&](int, int) { return uniform(rng) < 0.7f ? 0.1f : 0.9f; }),
      picture("checkerboard_1px.png", [](int row, int column) { return (row + column) % 2 ? 0.1f : 0.9f; }),
      picture("checkerboard_16px.png", [](int row, int column) { return (row / 16 + column / 16) % 2 ? 0.1f : 0.9f; }),
  };
  for (const GreyImage& image : hostile) {
    INFO(image.source);
    CHECK_THROWS_WITH(
        extract_surface(image, DrumFrame{0.084}, ProfileOptions{}),
        Catch::Contains(image.source) && (Catch::Contains("drum photo") || Catch::Contains("no free surface")));
  }
  const test::DrawnDrum drum;
  const std::vector<std::function<double(double)>> surfaces = {
      [](double x) { return 0.002 - std::tan(50.0 * M_PI / 180.0) * x; },
      [](double x) { return 0.001 - 0.022 * std::tanh(x / 0.012); }, [](double) { return -0.03; },  // nearly empty drum
      [](double) { return 0.03; },                                                                  // nearly full drum
  };
  for (const auto& surface : surfaces) {
    const SurfaceProfile profile = extract_surface(test::draw_surface(drum, surface), DrumFrame{drum.diameter}, {});
    CHECK(profile.bed_share > 0.99);
    CHECK(profile.bed_solidity > 0.99);
    CHECK(profile.surface_cover == 1.0);
  }
}

TEST_CASE("a drum diameter outside 1 mm .. 100 m is refused by the surface extraction and the occupancy image") {
  const test::DrawnDrum drum;
  const GreyImage photo = test::draw_surface(drum, [](double x) { return -0.5 * x; });
  for (const double diameter : {1e-300, 9e-4, 101.0, 1e300}) {
    INFO("diameter " << diameter);
    CHECK_THROWS_WITH(extract_surface(photo, DrumFrame{diameter}, ProfileOptions{}),
                      Catch::Contains("drum diameter") && Catch::Contains("1 mm .. 100 m"));
    CHECK_THROWS_WITH(OccupancyAccumulator(DrumFrame{diameter}, 64), Catch::Contains("drum diameter"));
  }
  // The angle of a drawn surface does not depend on the scale: the ends of the range give it too.
  for (const double diameter : {1e-3, 100.0}) {
    const SurfaceLine line = fit_surface_line(extract_surface(photo, DrumFrame{diameter}, ProfileOptions{}));
    CHECK(std::abs(line.angle_deg + std::atan(0.5) * 180.0 / M_PI) < 0.5);
  }
}

TEST_CASE("an 8-bit BMP reads all 256 palette entries with the OS/2 header as with the Windows header") {
  const fs::path dir = hostile_images_scratch("palette");
  for (const bool core : {true, false}) {
    // 16 x 16 pixels holding the indices 0..255; entry i is the grey level 255 - i, so an entry left
    // unset (0) is told apart from the last ones.
    const std::uint32_t header = core ? 12 : 40, entry = core ? 3 : 4, offset = 14 + header + 256 * entry;
    std::string bmp = "BM";
    put_le(bmp, offset + 256, 4);
    put_le(bmp, 0, 4);
    put_le(bmp, offset, 4);
    put_le(bmp, header, 4);
    put_le(bmp, 16, core ? 2 : 4);
    put_le(bmp, 16, core ? 2 : 4);
    put_le(bmp, 1, 2);
    put_le(bmp, 8, 2);
    if (!core) bmp.append(24, '\0');
    for (int i = 0; i < 256; ++i) {  // blue, green, red (and a reserved 0 with the Windows header)
      bmp.append(3, static_cast<char>(255 - i));
      if (!core) bmp.push_back('\0');
    }
    for (int i = 0; i < 256; ++i) bmp.push_back(static_cast<char>(i));  // bottom-up rows of 16
    write_bytes(dir / "palette.bmp", bmp);
    INFO((core ? "OS/2 header" : "Windows header"));
    const GreyImage read = read_grey_image(dir / "palette.bmp");
    REQUIRE(read.width == 16);
    int wrong = 0;
    for (int row = 0; row < 16; ++row)
      for (int column = 0; column < 16; ++column) {
        const int index = (15 - row) * 16 + column;
        wrong += read.value[static_cast<std::size_t>(row) * 16 + column] != static_cast<float>(255 - index) / 255.0f;
      }
    CHECK(wrong == 0);
  }
}

TEST_CASE("a JPEG with stray bytes between its header segments decodes to the same pixels") {
  const fs::path dir = hostile_images_scratch("stray");
  const std::string jpeg = encode_jpeg(to_rgb(small_drum()), 90);
  REQUIRE(jpeg.compare(0, 4, "\xFF\xD8\xFF\xE0") == 0);  // Start Of Image, then the JFIF segment
  const std::size_t after_jfif = 4 + (static_cast<unsigned char>(jpeg[4]) << 8 | static_cast<unsigned char>(jpeg[5]));
  write_bytes(dir / "plain.jpg", jpeg);
  write_bytes(dir / "stray.jpg", std::string(jpeg).insert(after_jfif, "stray padding"));
  const GreyImage plain = read_grey_image(dir / "plain.jpg"), stray = read_grey_image(dir / "stray.jpg");
  REQUIRE(stray.width == plain.width);
  CHECK(stray.value == plain.value);
}
