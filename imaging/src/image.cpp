// Image files through Debian's stb (libstb-dev): stb_image reads, stb_image_write writes PNG.
// This is the one translation unit that holds the stb implementations.
#include "demfit/imaging/image.hpp"

#include <algorithm>
#include <cmath>
#include <climits>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "image_container.hpp"

// stb_image allocates through a byte budget (namespace budget below): a file whose compressed data
// expands beyond what its declared size needs (a zlib stream longer than the picture, corrupt
// JPEG tables) makes stb fail with "outofmem" instead of taking the machine's memory.
namespace demfit::imaging::budget {
void* allocate(std::size_t size);
void* reallocate(void* block, std::size_t size);
void release(void* block);
}  // namespace demfit::imaging::budget
#define STBI_MALLOC(size) demfit::imaging::budget::allocate(size)
#define STBI_REALLOC(block, size) demfit::imaging::budget::reallocate(block, size)
#define STBI_FREE(block) demfit::imaging::budget::release(block)

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
namespace budget {
namespace {

// Bytes stb_image may hold at once in this thread, and how many it holds. Each block carries its
// size in a header of max_align_t's size, so that release and reallocate can account for it.
thread_local std::size_t limit_bytes = 0;
thread_local std::size_t live_bytes = 0;
constexpr std::size_t kHeader = alignof(std::max_align_t);

// Sets the budget for one decoding and restores "nothing allowed" afterwards.
class Scope {
 public:
  explicit Scope(std::size_t limit) { limit_bytes = limit; }
  ~Scope() { limit_bytes = 0; }
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;
};

std::size_t block_size(void* block) {
  std::size_t size = 0;
  std::memcpy(&size, static_cast<char*>(block) - kHeader, sizeof size);
  return size;
}

}  // namespace

void* allocate(std::size_t size) {
  if (size > limit_bytes || live_bytes > limit_bytes - size) return nullptr;
  char* raw = static_cast<char*>(std::malloc(size + kHeader));
  if (raw == nullptr) return nullptr;
  std::memcpy(raw, &size, sizeof size);
  live_bytes += size;
  return raw + kHeader;
}

void release(void* block) {
  if (block == nullptr) return;
  live_bytes -= block_size(block);
  std::free(static_cast<char*>(block) - kHeader);
}

void* reallocate(void* block, std::size_t size) {
  if (block == nullptr) return allocate(size);
  const std::size_t old_size = block_size(block);
  if (size > old_size && (size - old_size > limit_bytes || live_bytes > limit_bytes - (size - old_size)))
    return nullptr;
  char* raw = static_cast<char*>(std::realloc(static_cast<char*>(block) - kHeader, size + kHeader));
  if (raw == nullptr) return nullptr;
  std::memcpy(raw, &size, sizeof size);
  live_bytes = live_bytes - old_size + size;
  return raw + kHeader;
}

}  // namespace budget

namespace {

std::string quoted(const std::string& source) { return "image '" + source + "'"; }

std::string read_bytes(const std::filesystem::path& file, std::uintmax_t limit) {
  const std::string name = quoted(file.string());
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    throw std::runtime_error(name + " does not exist or is not a file; check the path");
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (!error && size > limit)
    throw std::runtime_error(name + " is " + std::to_string(size) + " bytes, above the " + std::to_string(limit >> 20) +
                             " MiB limit for a drum photo; crop it to the drum or save it compressed");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + name + "; check its read permission");
  std::string bytes;
  std::string chunk(std::size_t{1} << 20, '\0');
  while (in && bytes.size() <= limit) {  // reads at most one chunk past the limit
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    bytes.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (bytes.size() > limit)
    throw std::runtime_error(name + " is above the " + std::to_string(limit >> 20) +
                             " MiB limit for a drum photo; crop it to the drum or save it compressed");
  return bytes;
}

// Refuses a declared size above the limits before anything the size of the picture is allocated.
void check_declared_size(const container::Size& size, const ImageLimits& limits, const std::string& name) {
  const std::string declared = std::to_string(size.width) + " x " + std::to_string(size.height) + " pixels";
  std::ostringstream megapixels;
  megapixels << static_cast<double>(limits.pixels) / 1e6;
  if (size.width <= 0 || size.height <= 0)
    throw std::runtime_error(name + " declares " + declared + "; give a BMP, PNG or JPEG file with a picture in it");
  if (size.width > limits.side || size.height > limits.side || size.width * size.height > limits.pixels)
    throw std::runtime_error(name + " declares " + declared + ", above the limit of " + std::to_string(limits.side) +
                             " pixels a side and " + megapixels.str() +
                             " megapixels; crop the photo to the drum or scale it down");
}

// The declared size, checked against the limits, after the container checks of the format; a
// JPEG's `bytes` are cut at its End Of Image marker; an OS/2 BMP's are replaced by `rewritten`, the
// same picture with the Windows header. stb_image only ever sees a file whose container
// was checked here first: it trusts sizes, offsets and table counts, and Debian's stb_image 2.27
// writes past a JPEG Huffman table that declares more than 256 codes.
container::Size check_container(std::string_view& bytes, std::string& rewritten, const ImageLimits& limits,
                                const std::string& name) {
  container::Size size;
  switch (container::detect_format(bytes)) {
    case container::Format::bmp:
      size = container::bmp_declared_size(bytes, name);
      check_declared_size(size, limits, name);
      container::check_bmp_pixel_data(bytes, name);
      if (container::is_core_bmp(bytes)) {
        rewritten = container::windows_bmp_from_core(bytes);
        bytes = rewritten;
      }
      break;
    case container::Format::png:
      size = container::png_declared_size(bytes, name);
      check_declared_size(size, limits, name);
      container::check_png_chunks(bytes, name);
      break;
    case container::Format::jpeg: {
      const container::JpegLayout layout = container::jpeg_layout(bytes, name);
      size = layout.size;
      check_declared_size(size, limits, name);
      bytes = bytes.substr(0, layout.length);
      break;
    }
    case container::Format::other:
      throw std::runtime_error(name +
                               " cannot be decoded (its first bytes are not those of a BMP, PNG or JPEG file); "
                               "give a BMP, PNG or JPEG file");
  }
  return size;
}

void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

GreyImage read_grey_image(const std::filesystem::path& file, const ImageLimits& limits) {
  const std::string bytes = read_bytes(file, limits.file_bytes);
  return decode_grey_image(bytes, file.string(), limits);
}

GreyImage decode_grey_image(std::string_view bytes, const std::string& source, const ImageLimits& limits) {
  const std::string name = quoted(source);
  if (bytes.empty()) throw std::runtime_error(name + " is empty; give a BMP, PNG or JPEG file");
  if (bytes.size() > limits.file_bytes || bytes.size() > std::size_t{INT_MAX})
    throw std::runtime_error(name + " is " + std::to_string(bytes.size()) + " bytes, above the " +
                             std::to_string(limits.file_bytes >> 20) + " MiB limit for a drum photo");
  std::string rewritten;  // an OS/2 BMP rewritten with the Windows header
  const container::Size size = check_container(bytes, rewritten, limits, name);
  // stb holds at most the compressed file plus 16 bytes per declared pixel (4 channels of 16 bits,
  // twice: the inflated PNG rows and the image made from them) plus 64 MiB of tables and rows.
  const std::size_t limit = bytes.size() + 16 * static_cast<std::size_t>(size.width * size.height) + (64u << 20);
  budget::Scope scope(limit);
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                                                static_cast<int>(bytes.size()), &width, &height, &channels, 1);
  if (pixels == nullptr) {
    const std::string reason = stbi_failure_reason();
    if (reason == "outofdata")
      throw std::runtime_error(name + " is truncated (its data ends before the picture does); copy the file again");
    if (reason == "outofmem")
      throw std::runtime_error(name + " needs more than " + std::to_string(limit >> 20) + " MiB to decode its " +
                               std::to_string(size.width) + " x " + std::to_string(size.height) +
                               " pixels; the file is corrupt or not a plain photo: re-export it");
    throw std::runtime_error(name + " cannot be decoded (" + reason + "); give a BMP, PNG or JPEG file");
  }
  if (width != size.width || height != size.height) {
    stbi_image_free(pixels);
    throw std::runtime_error(name + " is corrupted (decoded " + std::to_string(width) + " x " + std::to_string(height) +
                             " pixels, its header declares " + std::to_string(size.width) + " x " +
                             std::to_string(size.height) + "); re-export it");
  }
  GreyImage image;
  image.width = width;
  image.height = height;
  image.source = source;
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
