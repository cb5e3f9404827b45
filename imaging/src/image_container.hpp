#pragma once
// Checks of an image file's container made before stb_image decodes it. stb_image trusts the
// container: it pads a truncated BMP or JPEG with zeros, ignores PNG chunk checksums and stops a
// JPEG at the first unexpected byte after its End Of Image marker. These checks refuse what stb
// would silently get wrong. Private to imaging (src/); read_grey_image is the public entry.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace demfit::imaging::container {

enum class Format { bmp, png, jpeg, other };

// The format named by the file's first bytes ("BM", the PNG signature, the JPEG SOI marker FF D8).
Format detect_format(std::string_view bytes);

// Width and height [px] declared by a BMP header (all header variants stb_image reads: 12-byte
// OS/2 BITMAPCOREHEADER, 40, 56, 108 and 124-byte Windows headers); height made positive (a
// negative one means rows stored top-down). Throws (one line naming `name`) when the header is cut
// short or declares a negative width.
struct Size {
  std::int64_t width = 0;
  std::int64_t height = 0;
};
Size bmp_declared_size(std::string_view bytes, const std::string& name);

// Width and height [px] declared by a PNG's IHDR chunk (the first chunk, PNG specification 11.2.2;
// after an Apple CgBI chunk if there is one).
// Throws (one line naming `name`) when the file ends before them or the first chunk is not IHDR.
Size png_declared_size(std::string_view bytes, const std::string& name);

// Throws (one line naming `name`) when an uncompressed BMP holds fewer bytes than its header
// declares: pixel data offset + row stride (padded to 4 bytes) x rows > file size.
void check_bmp_pixel_data(std::string_view bytes, const std::string& name);

// The same picture as a BMP with the 40-byte Windows header, for a BMP with the 12-byte OS/2
// header (3-byte palette entries become 4-byte ones). stb_image 2.27 counts an OS/2 palette 12
// bytes short and leaves the last four of 256 entries unset (index 255 read as 0), so OS/2 BMPs
// are decoded through this copy. Call after check_bmp_pixel_data.
std::string windows_bmp_from_core(std::string_view bytes);
bool is_core_bmp(std::string_view bytes);  // a BMP with the 12-byte OS/2 BITMAPCOREHEADER

// Throws (one line naming `name` and the chunk) when a PNG chunk's CRC-32 (PNG specification,
// section 5.3: over the chunk type and data) differs from the stored one, or when the file ends
// inside a chunk or before the IEND chunk.
void check_png_chunks(std::string_view bytes, const std::string& name);

// The JPEG's extent and size, found by walking its marker segments and entropy-coded scans (JPEG,
// ITU-T T.81 annex B): `length` = bytes up to and including the End Of Image marker (FF D9), so
// that bytes after it (phone trailers, appended data) are ignored; `size` = width and height of
// its frame header (SOFn). Huffman table segments are checked on the way (at most 256 codes a
// table). Throws (one line naming `name`) when the file ends before End Of Image (truncated), the
// marker structure is broken, a table is invalid or there is no frame header. Bytes other than FF
// between segments are skipped, as stb_image skips them.
struct JpegLayout {
  std::size_t length = 0;
  Size size;
};
JpegLayout jpeg_layout(std::string_view bytes, const std::string& name);

}  // namespace demfit::imaging::container
