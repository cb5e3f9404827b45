// Image files through Debian's stb (libstb-dev): stb_image reads, stb_image_write writes PNG.
// This is the one translation unit that holds the stb implementations.
#include "demfit/imaging/image.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#define STBI_NO_STDIO
#define STBI_ONLY_BMP
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#define STBI_WRITE_NO_STDIO
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace demfit::imaging {
namespace {

std::string read_bytes(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    throw std::runtime_error("image '" + file.string() + "' does not exist or is not a file; check the path");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open image '" + file.string() + "'; check its read permission");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::uint32_t little_endian(const std::string& bytes, std::size_t at, int size) {
  std::uint32_t v = 0;
  for (int k = size - 1; k >= 0; --k)
    v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(k)]);
  return v;
}

// stb_image pads a truncated file with zeros instead of failing (BMP and JPEG), so truncation is
// checked from the container itself: an uncompressed BMP must hold offset + stride * rows bytes;
// a JPEG must end with its End Of Image marker FF D9 (entropy-coded data cannot contain it, so it
// is searched for in the last 1 KiB to allow a little trailing padding).
bool looks_truncated(const std::string& bytes) {
  if (bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M') {
    if (bytes.size() < 54) return true;
    const std::uint32_t offset = little_endian(bytes, 10, 4);
    const std::uint32_t header = little_endian(bytes, 14, 4);
    if (header < 40) return false;  // old OS/2 header: leave it to stb
    const auto width = static_cast<std::int32_t>(little_endian(bytes, 18, 4));
    const auto height = static_cast<std::int32_t>(little_endian(bytes, 22, 4));
    const std::uint32_t bits = little_endian(bytes, 28, 2);
    const std::uint32_t compression = little_endian(bytes, 30, 4);
    if (compression != 0 && compression != 3) return false;  // RLE: size not known in advance
    const std::uint64_t stride = ((static_cast<std::uint64_t>(std::abs(width)) * bits + 31) / 32) * 4;
    return offset + stride * static_cast<std::uint64_t>(std::abs(height)) > bytes.size();
  }
  if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0xFF &&
      static_cast<unsigned char>(bytes[1]) == 0xD8) {
    const std::size_t from = bytes.size() > 1024 ? bytes.size() - 1024 : 2;
    for (std::size_t k = bytes.size() - 1; k > from; --k)
      if (static_cast<unsigned char>(bytes[k - 1]) == 0xFF && static_cast<unsigned char>(bytes[k]) == 0xD9)
        return false;
    return true;
  }
  return false;
}

void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

GreyImage read_grey_image(const std::filesystem::path& file) {
  const std::string bytes = read_bytes(file);
  if (bytes.empty()) throw std::runtime_error("image '" + file.string() + "' is empty; give a BMP, PNG or JPEG file");
  const std::string truncated =
      "image '" + file.string() + "' is truncated (its data ends before the picture does); copy the file again";
  if (looks_truncated(bytes)) throw std::runtime_error(truncated);
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                                                static_cast<int>(bytes.size()), &width, &height, &channels, 1);
  if (pixels == nullptr && std::string(stbi_failure_reason()) == "outofdata") throw std::runtime_error(truncated);
  if (pixels == nullptr)
    throw std::runtime_error("image '" + file.string() + "' cannot be decoded (" + stbi_failure_reason() +
                             "); give a BMP, PNG or JPEG file");
  GreyImage image;
  image.width = width;
  image.height = height;
  image.source = file.string();
  image.value.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (std::size_t k = 0; k < image.value.size(); ++k) image.value[k] = static_cast<float>(pixels[k]) / 255.0f;
  stbi_image_free(pixels);
  return image;
}

std::string encode_png(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw std::runtime_error(
        "cannot encode a PNG: the RGB image is empty or its buffer size is not 3 x width x height");
  std::string encoded;
  if (stbi_write_png_to_func(append_bytes, &encoded, image.width, image.height, 3, image.rgb.data(), 3 * image.width) ==
      0)
    throw std::runtime_error("cannot encode a PNG of " + std::to_string(image.width) + " x " +
                             std::to_string(image.height) + " pixels");
  return encoded;
}

std::string encode_jpeg(const RgbImage& image, int quality) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw std::runtime_error(
        "cannot encode a JPEG: the RGB image is empty or its buffer size is not 3 x width x height");
  if (quality < 1 || quality > 100)
    throw std::runtime_error("JPEG quality " + std::to_string(quality) + ": give 1..100");
  std::string encoded;
  if (stbi_write_jpg_to_func(append_bytes, &encoded, image.width, image.height, 3, image.rgb.data(), quality) == 0)
    throw std::runtime_error("cannot encode a JPEG of " + std::to_string(image.width) + " x " +
                             std::to_string(image.height) + " pixels");
  return encoded;
}

RgbImage to_rgb(const GreyImage& image) {
  RgbImage out;
  out.width = image.width;
  out.height = image.height;
  out.rgb.resize(3 * image.value.size());
  for (std::size_t k = 0; k < image.value.size(); ++k) {
    const float v = std::min(1.0f, std::max(0.0f, image.value[k]));
    const auto byte = static_cast<std::uint8_t>(std::lround(255.0f * v));
    out.rgb[3 * k] = out.rgb[3 * k + 1] = out.rgb[3 * k + 2] = byte;
  }
  return out;
}

}  // namespace demfit::imaging
