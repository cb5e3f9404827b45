#pragma once
// Raster images of a drum: a grey image read from a photo (BMP, PNG, JPEG through Debian's
// stb_image) and an RGB image written as PNG (stb_image_write). Row 0 is the top of the picture.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
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

// Limits on an image file, checked before any pixel is decoded: a few hundred bytes of a
// compressed file can declare billions of pixels (a decompression bomb). A drum photo cropped to
// the drum is far below them (the GranuDrum photos: 406 x 406 pixels, 167 KB).
struct ImageLimits {
  std::uintmax_t file_bytes = std::uintmax_t{256} << 20;  // 256 MiB read at most
  std::int64_t side = 20000;                              // [px] width and height each
  std::int64_t pixels = 50000000;                         // width x height (50 megapixels)
};

// Reads BMP, PNG or JPEG (colour is converted to luminance by stb_image). Throws
// std::runtime_error with one line naming the file and the fix when the file is missing,
// unreadable, larger than limits.file_bytes, declares more pixels than limits.side a side or
// limits.pixels in all (refused from the header, before decoding), is truncated (a BMP holding
// fewer pixel bytes than its header declares, of every header variant; a PNG ending before IEND;
// a JPEG ending before End Of Image), has a PNG chunk whose CRC-32 fails (the chunk is named), a
// JPEG Huffman table of more than 256 codes or a second JPEG frame header, or is not an image.
// Bytes after a JPEG's End Of Image marker (phone trailers) are ignored. The decoder's own
// allocations are capped at the file size + 16 bytes per declared pixel + 64 MiB, so corrupt
// compressed data cannot expand past that either.
GreyImage read_grey_image(const std::filesystem::path& file, const ImageLimits& limits = {});

// The same from the file's bytes in memory; `source` names the file in error messages.
GreyImage decode_grey_image(std::string_view bytes, const std::string& source, const ImageLimits& limits = {});

// CRC-32 as the PNG specification (annex D) defines it, over `bytes` (a chunk's type and data).
std::uint32_t png_crc32(std::string_view bytes);

// The PNG file content of `image`. imaging writes no files: callers write the bytes through the
// one atomic writer (identify/safe_output.hpp), which also keeps them inside the output folder.
std::string encode_png(const RgbImage& image);

// The JPEG file content of `image` at quality 1..100 (lossy; for previews and for tests of the
// JPEG reader).
std::string encode_jpeg(const RgbImage& image, int quality);

// The grey image as RGB (each channel = round(255 * value)).
RgbImage to_rgb(const GreyImage& image);

}  // namespace demfit::imaging
