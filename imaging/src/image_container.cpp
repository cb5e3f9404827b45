// Container checks made before stb_image decodes a file (image_container.hpp): BMP sizes, PNG
// chunk checksums, the extent of a JPEG up to its End Of Image marker.
#include "image_container.hpp"

#include <algorithm>
#include <array>
#include <utility>
#include <cstdio>
#include <stdexcept>

#include "demfit/imaging/image.hpp"

namespace demfit::imaging {

namespace {

// CRC-32 of ISO 3309 / ITU-T V.42 as the PNG specification (annex D) defines it: reflected
// polynomial 0xEDB88320, initial value and final XOR 0xFFFFFFFF.
constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

}  // namespace

std::uint32_t png_crc32(std::string_view bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const char b : bytes) c = kCrcTable[(c ^ static_cast<unsigned char>(b)) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

namespace container {
namespace {

unsigned byte_at(std::string_view bytes, std::size_t at) { return static_cast<unsigned char>(bytes[at]); }

std::uint32_t little_endian(std::string_view bytes, std::size_t at, int size) {
  std::uint32_t v = 0;
  for (int k = size - 1; k >= 0; --k) v = (v << 8) | byte_at(bytes, at + static_cast<std::size_t>(k));
  return v;
}

std::uint32_t big_endian(std::string_view bytes, std::size_t at, int size) {
  std::uint32_t v = 0;
  for (int k = 0; k < size; ++k) v = (v << 8) | byte_at(bytes, at + static_cast<std::size_t>(k));
  return v;
}

std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08X", value);
  return text;
}

std::runtime_error truncated(const std::string& name, const std::string& detail) {
  return std::runtime_error(name + " is truncated (" + detail + "); copy the file again");
}

std::runtime_error corrupt(const std::string& name, const std::string& detail) {
  return std::runtime_error(name + " is corrupted (" + detail + "); copy the file again or re-export it");
}

// A chunk type as text; bytes that are not letters are shown as '?' (a damaged type).
std::string chunk_type(std::string_view bytes, std::size_t at) {
  std::string type;
  for (std::size_t k = 0; k < 4; ++k) {
    const unsigned c = byte_at(bytes, at + k);
    type.push_back(((c | 0x20u) >= 'a' && (c | 0x20u) <= 'z') ? static_cast<char>(c) : '?');
  }
  return type;
}

}  // namespace

Format detect_format(std::string_view bytes) {
  if (bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M') return Format::bmp;
  if (bytes.size() >= 8 && bytes.substr(0, 8) == std::string_view("\x89PNG\r\n\x1A\n", 8)) return Format::png;
  if (bytes.size() >= 2 && byte_at(bytes, 0) == 0xFF && byte_at(bytes, 1) == 0xD8) return Format::jpeg;
  return Format::other;
}

Size bmp_declared_size(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 26)
    throw truncated(name, "the BMP header is cut short at " + std::to_string(bytes.size()) + " bytes");
  const std::uint32_t header = little_endian(bytes, 14, 4);
  Size size;
  if (header == 12) {  // OS/2 BITMAPCOREHEADER: unsigned 16-bit width and height, rows bottom-up
    size.width = little_endian(bytes, 18, 2);
    size.height = little_endian(bytes, 20, 2);
    return size;
  }
  size.width = static_cast<std::int32_t>(little_endian(bytes, 18, 4));
  size.height = static_cast<std::int32_t>(little_endian(bytes, 22, 4));
  if (size.width < 0) throw corrupt(name, "the BMP header declares a negative width " + std::to_string(size.width));
  if (size.height < 0) size.height = -size.height;  // top-down rows
  return size;
}

Size png_declared_size(std::string_view bytes, const std::string& name) {
  std::size_t at = 8;
  // Apple's CgBI chunk (iPhone-optimised PNGs, which stb_image reads) may come before IHDR.
  if (bytes.size() >= 24 && bytes.substr(12, 4) == "CgBI") at += 12 + big_endian(bytes, 8, 4);
  if (bytes.size() < at + 16)
    throw truncated(name, "the PNG ends at byte " + std::to_string(bytes.size()) + " inside its header");
  if (bytes.substr(at + 4, 4) != "IHDR")
    throw corrupt(name, "the first PNG chunk is '" + chunk_type(bytes, at + 4) + "', not 'IHDR'");
  return {big_endian(bytes, at + 8, 4), big_endian(bytes, at + 12, 4)};
}

void check_bmp_pixel_data(std::string_view bytes, const std::string& name) {
  const Size size = bmp_declared_size(bytes, name);
  const std::uint64_t header = little_endian(bytes, 14, 4);
  if (bytes.size() < 14 + header)
    throw truncated(name, "the " + std::to_string(header) + "-byte BMP header is cut short at " +
                              std::to_string(bytes.size()) + " bytes");
  const bool core = header == 12;
  if (!core && bytes.size() < 34) throw truncated(name, "the BMP header is cut short");
  const std::uint32_t bits = little_endian(bytes, core ? 24 : 28, 2);
  const std::uint32_t compression = core ? 0 : little_endian(bytes, 30, 4);
  if (compression != 0 && compression != 3) return;  // RLE or embedded JPEG/PNG: stb_image refuses them
  const std::uint64_t offset = little_endian(bytes, 10, 4);
  if (offset < 14 + header)
    throw corrupt(name, "the BMP pixel data offset " + std::to_string(offset) + " lies inside the " +
                            std::to_string(header) + "-byte header");
  const std::uint64_t stride = (static_cast<std::uint64_t>(size.width) * bits + 31) / 32 * 4;
  const std::uint64_t needed = offset + stride * static_cast<std::uint64_t>(size.height);
  if (needed > bytes.size())
    throw truncated(name, "its header declares " + std::to_string(size.width) + " x " + std::to_string(size.height) +
                              " pixels of " + std::to_string(bits) + " bits, " + std::to_string(needed) +
                              " bytes with the header, but the file holds " + std::to_string(bytes.size()));
}

bool is_core_bmp(std::string_view bytes) { return bytes.size() >= 18 && little_endian(bytes, 14, 4) == 12; }

std::string windows_bmp_from_core(std::string_view bytes) {
  const std::uint32_t width = little_endian(bytes, 18, 2), height = little_endian(bytes, 20, 2);
  const std::uint32_t bits = little_endian(bytes, 24, 2), offset = little_endian(bytes, 10, 4);
  const std::uint32_t entries = bits <= 8 ? std::min<std::uint32_t>(1u << bits, (offset - 26) / 3) : 0;
  const std::uint32_t stride = (width * bits + 31) / 32 * 4, data = stride * height;
  const std::uint32_t new_offset = 14 + 40 + 4 * entries;
  std::string out = "BM";
  auto put = [&out](std::uint32_t value, int size) {
    for (int k = 0; k < size; ++k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xFFu));
  };
  put(new_offset + data, 4);
  put(0, 4);
  put(new_offset, 4);
  for (const auto& [value, size] : {std::pair{40u, 4},
                                    {width, 4},
                                    {height, 4},
                                    {1u, 2},
                                    {bits, 2},
                                    {0u, 4},
                                    {data, 4},
                                    {0u, 4},
                                    {0u, 4},
                                    {entries, 4},
                                    {0u, 4}})
    put(value, size);
  for (std::uint32_t k = 0; k < entries; ++k) {
    out.append(bytes.substr(26 + 3 * k, 3));
    out.push_back('\0');
  }
  out.append(bytes.substr(offset, data));
  return out;
}

void check_png_chunks(std::string_view bytes, const std::string& name) {
  std::size_t at = 8;
  for (int index = 1;; ++index) {
    if (at + 8 > bytes.size())
      throw truncated(name, "the PNG ends at byte " + std::to_string(bytes.size()) + " before its IEND chunk");
    const std::uint64_t length = big_endian(bytes, at, 4);
    const std::string type = chunk_type(bytes, at + 4);
    const std::string where =
        "PNG chunk '" + type + "' (chunk " + std::to_string(index) + ", at byte " + std::to_string(at) + ")";
    if (length > 0x7FFFFFFFu) throw corrupt(name, where + " declares " + std::to_string(length) + " bytes");
    if (at + 12 + length > bytes.size())
      throw truncated(name, "the file ends inside " + where + " of " + std::to_string(length) + " bytes");
    const std::uint32_t stored = big_endian(bytes, at + 8 + length, 4);
    const std::uint32_t computed = png_crc32(bytes.substr(at + 4, 4 + length));
    if (stored != computed)
      throw corrupt(name, where + " fails its CRC-32 check: stored " + hex(stored) + ", computed " + hex(computed));
    if (type == "IEND") return;
    at += 12 + length;
  }
}

// The entropy-coded data of a scan ends at the first marker other than a stuffed byte (FF 00) or a
// restart marker (FF D0..D7) (T.81 section B.1.1.5). Returns the position of that marker's FF.
std::size_t end_of_scan(std::string_view bytes, std::size_t at, const std::string& name) {
  while (true) {
    if (at + 1 >= bytes.size()) throw truncated(name, "the JPEG ends inside its image data, before End Of Image");
    if (byte_at(bytes, at) != 0xFF) {
      ++at;
      continue;
    }
    const unsigned next = byte_at(bytes, at + 1);
    if (next == 0x00 || (next >= 0xD0 && next <= 0xD7)) {
      at += 2;
    } else if (next == 0xFF) {
      ++at;  // fill byte before a marker
    } else {
      return at;
    }
  }
}

// A Define Huffman Table segment (T.81 section B.2.4.2): each table's class and destination, its
// 16 code counts and as many symbols as they add up to, at most 256 (one per byte value). stb_image
// does not check that bound and writes past its tables when it is exceeded.
void check_huffman_tables(std::string_view bytes, std::size_t at, std::size_t end, const std::string& name) {
  while (at < end) {
    const std::string where = "JPEG Huffman table at byte " + std::to_string(at);
    if (at + 17 > end) throw corrupt(name, where + " is cut short by its segment");
    const unsigned kind = byte_at(bytes, at);
    if ((kind >> 4) > 1 || (kind & 15u) > 3) throw corrupt(name, where + " has class/destination " + hex(kind));
    std::size_t symbols = 0;
    for (std::size_t k = 1; k <= 16; ++k) symbols += byte_at(bytes, at + k);
    if (symbols > 256) throw corrupt(name, where + " declares " + std::to_string(symbols) + " codes, at most 256");
    at += 17 + symbols;
  }
  if (at != end) throw corrupt(name, "a JPEG Huffman table runs past its segment");
}

// Start Of Frame markers (T.81 table B.1): C0..CF except DHT (C4), JPG (C8) and DAC (CC).
bool is_frame_header(unsigned marker) {
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

JpegLayout jpeg_layout(std::string_view bytes, const std::string& name) {
  JpegLayout layout;
  bool has_frame = false;
  std::size_t at = 2;  // after Start Of Image
  while (true) {
    if (at >= bytes.size())
      throw truncated(name, "the JPEG ends at byte " + std::to_string(at) + " before End Of Image");
    // Bytes other than FF between segments are skipped one by one, as stb_image does, so that every
    // segment stb_image will read is the one checked here.
    if (byte_at(bytes, at) != 0xFF) {
      ++at;
      continue;
    }
    while (at < bytes.size() && byte_at(bytes, at) == 0xFF) ++at;  // fill bytes
    if (at >= bytes.size()) throw truncated(name, "the JPEG ends inside a marker, before End Of Image");
    const unsigned marker = byte_at(bytes, at++);
    if (marker == 0xD9) {  // End Of Image
      if (!has_frame) throw corrupt(name, "the JPEG has no frame header (SOF marker) before End Of Image");
      layout.length = at;
      return layout;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // markers without a length
    if (marker == 0x00 || marker == 0xD8)
      throw corrupt(name, "JPEG marker " + hex(0xFF00u | marker) + " at byte " + std::to_string(at - 2) +
                              " is not allowed there");
    if (at + 2 > bytes.size()) throw truncated(name, "the JPEG ends inside a segment header");
    const std::size_t length = big_endian(bytes, at, 2);
    if (length < 2)
      throw corrupt(name, "JPEG segment at byte " + std::to_string(at - 2) + " declares a length below 2");
    if (at + length > bytes.size())
      throw truncated(name, "the JPEG ends inside a segment at byte " + std::to_string(at - 2));
    if (marker == 0xC4) check_huffman_tables(bytes, at + 2, at + length, name);
    if (is_frame_header(marker)) {
      if (has_frame) throw corrupt(name, "a second JPEG frame header at byte " + std::to_string(at - 2));
      if (length < 8) throw corrupt(name, "the JPEG frame header at byte " + std::to_string(at - 2) + " is too short");
      layout.size = {big_endian(bytes, at + 5, 2), big_endian(bytes, at + 3, 2)};
      has_frame = true;
    }
    at += length;
    if (marker == 0xDA) at = end_of_scan(bytes, at, name);  // Start Of Scan: entropy-coded data follows
  }
}

}  // namespace container
}  // namespace demfit::imaging
