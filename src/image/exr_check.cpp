#include "image/exr_check.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "image/formats.h"

namespace tuneray::detail {

namespace {

constexpr uint32_t kTiledFlag = 0x200, kLongNamesFlag = 0x400, kDeepFlag = 0x800,
                   kMultiPartFlag = 0x1000;

// Scan lines per chunk of each compression (OpenEXR's numbering).
std::optional<int64_t> lines_per_chunk(uint8_t compression) {
  switch (compression) {
    case 0:  // none
    case 1:  // RLE
    case 2:  // ZIPS
      return 1;
    case 3:  // ZIP
    case 5:  // PXR24
      return 16;
    case 4:  // PIZ
    case 6:  // B44
    case 7:  // B44A
    case 8:  // DWAA
      return 32;
    case 9:  // DWAB
      return 256;
    default:
      return std::nullopt;
  }
}

class HeaderReader {
 public:
  HeaderReader(const std::string& path, std::istream& in, uint64_t size)
      : path_(path), in_(in), size_(size) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw ImageError(path_ + ": cannot read EXR: " + what);
  }
  uint64_t remaining() const { return size_ - at_; }

  std::string bytes(size_t n) {
    if (remaining() < n) fail("the header ends early");
    std::string v(n, '\0');
    if (!in_.read(v.data(), static_cast<std::streamsize>(n))) fail("the header ends early");
    at_ += n;
    return v;
  }
  void skip(uint64_t n) {
    if (remaining() < n) fail("the header ends early");
    in_.seekg(static_cast<std::streamoff>(n), std::ios::cur);
    if (!in_) fail("the header ends early");
    at_ += n;
  }
  uint32_t u32() { return as_u32(bytes(4), 0); }
  // A null-terminated name of at most `longest` characters (empty at the header's end).
  std::string name(size_t longest) {
    std::string s;
    for (;;) {
      char c = bytes(1)[0];
      if (c == '\0') return s;
      if (s.size() == longest) fail("an attribute name is longer than the format allows");
      s += c;
    }
  }

  static uint32_t as_u32(const std::string& v, size_t offset) {
    uint32_t u = 0;
    for (int k = 3; k >= 0; --k) u = (u << 8) | static_cast<uint8_t>(v[offset + k]);
    return u;
  }
  static int32_t as_i32(const std::string& v, size_t offset) {
    uint32_t u = as_u32(v, offset);
    int32_t s;
    std::memcpy(&s, &u, sizeof s);
    return s;
  }

 private:
  const std::string& path_;
  std::istream& in_;
  uint64_t size_;
  uint64_t at_ = 0;
};

}  // namespace

void check_exr_header(const std::string& path, std::istream& stream, uint64_t file_size) {
  HeaderReader in(path, stream, file_size);
  if (in.u32() != 20000630u) in.fail("the magic number is wrong");
  const uint32_t version = in.u32();
  if ((version & 0xff) != 2) in.fail("version " + std::to_string(version & 0xff) + " is unknown");
  const size_t longest_name = version & kLongNamesFlag ? 255 : 31;

  std::optional<std::string> data_window, tiles;
  std::optional<uint8_t> compression;
  for (;;) {
    std::string name = in.name(longest_name);
    if (name.empty()) break;
    std::string type = in.name(longest_name);
    if (type.empty()) in.fail("attribute '" + name + "' has no type");
    const uint32_t size = in.u32();
    if (size > in.remaining())
      in.fail("attribute '" + name + "' says it has " + std::to_string(size) +
              " bytes, more than the file has left");
    if (name == "dataWindow" && type == "box2i" && size == 16)
      data_window = in.bytes(size);
    else if (name == "compression" && type == "compression" && size == 1)
      compression = static_cast<uint8_t>(in.bytes(1)[0]);
    else if (name == "tiles" && type == "tiledesc" && size == 9)
      tiles = in.bytes(size);
    else
      in.skip(size);
  }
  // Multi-part and deep files have more headers and other chunk tables; OpenEXR checks those
  // itself, and the attribute sizes above are what it would have allocated first.
  if (version & (kMultiPartFlag | kDeepFlag)) return;
  if (!data_window) in.fail("there is no dataWindow attribute");
  if (!compression) in.fail("there is no compression attribute");
  const int64_t width =
      int64_t{HeaderReader::as_i32(*data_window, 8)} - HeaderReader::as_i32(*data_window, 0) + 1;
  const int64_t height =
      int64_t{HeaderReader::as_i32(*data_window, 12)} - HeaderReader::as_i32(*data_window, 4) + 1;
  check_dimensions(path, width, height);

  int64_t chunks = 0;
  if (version & kTiledFlag) {
    if (!tiles) in.fail("a tiled file without a tiles attribute");
    const int64_t tile_w = static_cast<uint32_t>(HeaderReader::as_i32(*tiles, 0));
    const int64_t tile_h = static_cast<uint32_t>(HeaderReader::as_i32(*tiles, 4));
    if (tile_w < 1 || tile_h < 1) in.fail("tiles of zero size");
    // The first level alone; mipmap levels only add chunks.
    chunks = ((width + tile_w - 1) / tile_w) * ((height + tile_h - 1) / tile_h);
  } else {
    std::optional<int64_t> lines = lines_per_chunk(*compression);
    if (!lines) in.fail("compression " + std::to_string(*compression) + " is unknown");
    chunks = (height + *lines - 1) / *lines;
  }
  // One 8-byte offset per chunk follows the header, then at least 8 bytes per chunk of data.
  if (static_cast<uint64_t>(chunks) * 16 > in.remaining())
    in.fail("the header promises " + std::to_string(chunks) + " chunks of pixels but only " +
            std::to_string(in.remaining()) + " bytes follow it (truncated?)");
}

void check_exr_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (!in || ec) throw ImageError(path + ": cannot open the file");
  check_exr_header(path, in, size);
}

}  // namespace tuneray::detail
