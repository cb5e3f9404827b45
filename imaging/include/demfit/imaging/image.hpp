#pragma once
// Raster images of a drum: a grey image read from a photo (BMP, PNG, JPEG through Debian's
// stb_image) and an RGB image written as PNG (stb_image_write). Row 0 is the top of the picture.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace demfit::imaging {

// Grey levels, row-major (index = row * width + column), row 0 = top of the picture,
// 0 = black .. 1 = white.
struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<float> value;
  std::string source;  // file it was read from (for error messages); empty for an image made in memory
};

// 8-bit RGB, row-major, 3 bytes per pixel (red, green, blue), row 0 = top.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // size 3 * width * height
};

// Reads BMP, PNG or JPEG (colour is converted to luminance by stb_image). Throws
// std::runtime_error with one line naming the file and the fix when the file is missing,
// unreadable, truncated or not an image.
GreyImage read_grey_image(const std::filesystem::path& file);

// Writes `image` as PNG atomically: to a temporary name beside `file`, then renamed into place,
// so a reader never sees a half-written picture. Throws std::runtime_error (one line) on failure.
void write_png(const std::filesystem::path& file, const RgbImage& image);

// The grey image as RGB (each channel = round(255 * value)).
RgbImage to_rgb(const GreyImage& image);

}  // namespace demfit::imaging
