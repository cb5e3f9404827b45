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

// The PNG file content of `image`. imaging writes no files: callers write the bytes through the
// one atomic writer (identify/safe_output.hpp), which also keeps them inside the output folder.
std::string encode_png(const RgbImage& image);

// The JPEG file content of `image` at quality 1..100 (lossy; for previews and for tests of the
// JPEG reader).
std::string encode_jpeg(const RgbImage& image, int quality);

// The grey image as RGB (each channel = round(255 * value)).
RgbImage to_rgb(const GreyImage& image);

}  // namespace demfit::imaging
