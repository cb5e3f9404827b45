// Image files: PNG encoded by encode_png and a BMP written by the test are read back through
// stb_image; broken files give one-line errors naming the file and the fix.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "demfit/imaging/image.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "drawn_images.hpp"

using namespace demfit::imaging;
namespace fs = std::filesystem;

namespace {

fs::path image_files_scratch(const std::string& name) {
  const fs::path dir = fs::path(DEMFIT_BINARY_DIR) / "test_imaging_scratch" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void put(std::string& out, std::uint32_t value, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xFF));
}

// A 24-bit uncompressed BMP (BITMAPINFOHEADER, rows stored bottom-up, padded to 4 bytes).
std::string encode_bmp_with_resolution(const GreyImage& image) {
  const std::uint32_t stride = (3 * image.width + 3) / 4 * 4, data = stride * image.height;
  std::string out = "BM";
  put(out, 54 + data, 4);
  put(out, 0, 4);
  put(out, 54, 4);
  put(out, 40, 4);
  put(out, image.width, 4);
  put(out, image.height, 4);
  put(out, 1, 2);
  put(out, 24, 2);
  put(out, 0, 4);
  put(out, data, 4);
  put(out, 2835, 4);
  put(out, 2835, 4);
  put(out, 0, 4);
  put(out, 0, 4);
  for (int row = image.height - 1; row >= 0; --row) {
    for (int column = 0; column < image.width; ++column) {
      const auto byte =
          static_cast<char>(std::lround(255.0f * image.value[static_cast<std::size_t>(row) * image.width + column]));
      out.append(3, byte);
    }
    out.append(stride - 3 * image.width, '\0');
  }
  return out;
}

using test::write_bytes;

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

double max_difference(const GreyImage& a, const GreyImage& b) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.value.size(); ++k)
    worst = std::max(worst, std::abs(static_cast<double>(a.value[k] - b.value[k])));
  return worst;
}

}  // namespace

TEST_CASE("a PNG encoded by encode_png reads back with the same grey levels to 8-bit rounding") {
  const fs::path dir = image_files_scratch("png");
  const GreyImage drawn = test::draw_surface(test::DrawnDrum{}, [](double x) { return -0.6 * x; });
  test::write_png(dir / "drum.png", to_rgb(drawn));
  CHECK(fs::directory_iterator(dir) != fs::directory_iterator());
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);  // no temporary left
  const GreyImage read = read_grey_image(dir / "drum.png");
  REQUIRE(read.width == drawn.width);
  REQUIRE(read.height == drawn.height);
  CHECK(read.source == (dir / "drum.png").string());
  CHECK(max_difference(read, drawn) <= 0.5 / 255.0 + 1e-6);
}

TEST_CASE("a BMP drawn with a known surface reads back with row 0 at the top and gives that surface") {
  const fs::path dir = image_files_scratch("bmp");
  const test::DrawnDrum drum;
  const auto surface = [](double x) { return 0.003 - std::tan(33.0 * M_PI / 180.0) * x; };
  const GreyImage drawn = test::draw_surface(drum, surface);
  write_bytes(dir / "drum.bmp", encode_bmp_with_resolution(drawn));
  const GreyImage read = read_grey_image(dir / "drum.bmp");
  REQUIRE(read.width == drum.pixels);
  CHECK(max_difference(read, drawn) <= 0.5 / 255.0 + 1e-6);
  const SurfaceProfile profile = extract_surface(read, DrumFrame{drum.diameter}, ProfileOptions{});
  CHECK(std::abs(-fit_surface_line(profile).angle_deg - 33.0) < 0.5);
  CHECK(test::rms_against(profile, surface) < 0.25 * drum.pixel_size());
}

TEST_CASE("a JPEG of a drawn drum reads back close to the drawing and gives its surface") {
  const fs::path dir = image_files_scratch("jpeg");
  const test::DrawnDrum drum;
  const auto surface = [](double x) { return -0.001 - std::tan(28.0 * M_PI / 180.0) * x; };
  const GreyImage drawn = test::draw_surface(drum, surface);
  write_bytes(dir / "drum.jpg", encode_jpeg(to_rgb(drawn), 95));
  const GreyImage read = read_grey_image(dir / "drum.jpg");
  REQUIRE(read.width == drum.pixels);
  // Lossy: compression ringing stays near the edge; the surface is still within a pixel.
  const SurfaceProfile profile = extract_surface(read, DrumFrame{drum.diameter}, ProfileOptions{});
  CHECK(std::abs(-fit_surface_line(profile).angle_deg - 28.0) < 0.5);
  CHECK(test::rms_against(profile, surface) < drum.pixel_size());
  const std::string jpeg = read_bytes(dir / "drum.jpg");
  write_bytes(dir / "cut.jpg", jpeg.substr(0, jpeg.size() * 3 / 4));
  CHECK_THROWS_WITH(read_grey_image(dir / "cut.jpg"), Catch::Contains("cut.jpg") && Catch::Contains("truncated"));
}

TEST_CASE("truncated BMP and PNG files are refused as truncated, naming the file") {
  const fs::path dir = image_files_scratch("truncated");
  const GreyImage drawn = test::draw_surface(test::DrawnDrum{}, [](double x) { return -0.6 * x; });
  const std::string bmp = encode_bmp_with_resolution(drawn);
  write_bytes(dir / "cut.bmp", bmp.substr(0, bmp.size() * 2 / 3));
  CHECK_THROWS_WITH(read_grey_image(dir / "cut.bmp"), Catch::Contains("cut.bmp") && Catch::Contains("truncated"));
  test::write_png(dir / "whole.png", to_rgb(drawn));
  const std::string png = read_bytes(dir / "whole.png");
  write_bytes(dir / "cut.png", png.substr(0, png.size() / 2));
  CHECK_THROWS_WITH(read_grey_image(dir / "cut.png"), Catch::Contains("cut.png") && Catch::Contains("truncated"));
}

TEST_CASE("a missing file, an empty file and a file that is not an image are refused with the fix") {
  const fs::path dir = image_files_scratch("not_image");
  CHECK_THROWS_WITH(read_grey_image(dir / "absent.png"),
                    Catch::Contains("absent.png") && Catch::Contains("check the path"));
  write_bytes(dir / "empty.bmp", "");
  CHECK_THROWS_WITH(read_grey_image(dir / "empty.bmp"),
                    Catch::Contains("empty.bmp") && Catch::Contains("BMP, PNG or JPEG"));
  write_bytes(dir / "notes.png", "x_mm,z_mm\n1,2\n");
  CHECK_THROWS_WITH(read_grey_image(dir / "notes.png"),
                    Catch::Contains("notes.png") && Catch::Contains("cannot be decoded"));
}
