// Zip archive verification (core/zip_check.hpp). Every offset and size read
// from the file is bounds-checked before use.
#include "core/zip_check.hpp"

#include <zlib.h>

#include <array>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
namespace {

constexpr std::uint32_t kLocal = 0x04034b50, kCentral = 0x02014b50, kEnd = 0x06054b50;
constexpr std::uint32_t kEnd64 = 0x06064b50, kLocator64 = 0x07064b50;

std::array<std::uint32_t, 256> make_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}

class Reader {
 public:
  Reader(std::string_view bytes, const std::string& name) : b_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const { throw Error::in(name_, "damaged archive: " + what); }

  std::uint64_t u(std::uint64_t at, int size) const {
    if (at > b_.size() || std::uint64_t(size) > b_.size() - at) fail("a record reaches past the end of the file");
    std::uint64_t v = 0;
    for (int i = size - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b_[std::size_t(at) + i]);
    return v;
  }
  std::string_view span(std::uint64_t at, std::uint64_t size) const {
    if (at > b_.size() || size > b_.size() - at) fail("a record reaches past the end of the file");
    return b_.substr(std::size_t(at), std::size_t(size));
  }
  std::uint64_t size() const { return b_.size(); }

 private:
  std::string_view b_;
  const std::string& name_;
};

// CRC-32 of the raw-deflate `data`, inflated to exactly `size` bytes in pieces
// (nothing the size of the record is allocated); false if it does not inflate.
bool inflated_crc(std::string_view data, std::uint64_t size, std::uint32_t& crc) {
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return false;
  std::vector<unsigned char> out(1 << 16);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = uInt(data.size());
  std::uint64_t total = 0;
  crc = 0;
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = out.data();
    z.avail_out = uInt(out.size());
    rc = inflate(&z, Z_NO_FLUSH);
    const std::size_t got = out.size() - z.avail_out;
    total += got;
    if (total > size) break;
    crc = ptnet::crc32(std::string_view(reinterpret_cast<const char*>(out.data()), got), crc);
    if (rc == Z_BUF_ERROR && got > 0) rc = Z_OK;  // more output room needed
  }
  inflateEnd(&z);
  return rc == Z_STREAM_END && total == size;
}

}  // namespace

std::uint32_t crc32(std::string_view bytes, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> table = make_table();
  crc = ~crc;
  for (unsigned char c : bytes) crc = table[(crc ^ c) & 0xff] ^ (crc >> 8);
  return ~crc;
}

int verify_zip(std::string_view bytes, const std::string& name) {
  Reader r(bytes, name);
  if (r.size() < 22) r.fail("too short for a zip archive (" + std::to_string(r.size()) + " bytes)");
  // End of central directory: the last signature within the final 64 kB + 22 bytes.
  std::uint64_t end = r.size() - 22;
  const std::uint64_t lowest = r.size() > 22 + 65535 ? r.size() - 22 - 65535 : 0;
  while (r.u(end, 4) != kEnd) {
    if (end == lowest) r.fail("no end-of-central-directory record (truncated, or not a zip archive)");
    --end;
  }
  std::uint64_t entries = r.u(end + 10, 2), dir_size = r.u(end + 12, 4), dir_at = r.u(end + 16, 4);
  if (entries == 0xffff || dir_size == 0xffffffff || dir_at == 0xffffffff) {  // zip64
    if (end < 20 || r.u(end - 20, 4) != kLocator64) r.fail("zip64 locator missing");
    const std::uint64_t end64 = r.u(end - 20 + 8, 8);
    if (r.u(end64, 4) != kEnd64) r.fail("zip64 end-of-central-directory record missing");
    entries = r.u(end64 + 32, 8);
    dir_size = r.u(end64 + 40, 8);
    dir_at = r.u(end64 + 48, 8);
  }
  if (dir_at > r.size() || dir_size > r.size() - dir_at) r.fail("central directory outside the file");
  if (entries > dir_size / 46) r.fail("more entries than the central directory can hold");
  std::uint64_t at = dir_at;
  for (std::uint64_t i = 0; i < entries; ++i) {
    if (r.u(at, 4) != kCentral) r.fail("central directory entry " + std::to_string(i) + " has a bad signature");
    const std::uint64_t flags = r.u(at + 8, 2), method = r.u(at + 10, 2), crc = r.u(at + 16, 4);
    std::uint64_t csize = r.u(at + 20, 4), usize = r.u(at + 24, 4), local = r.u(at + 42, 4);
    const std::uint64_t name_len = r.u(at + 28, 2), extra_len = r.u(at + 30, 2), comment_len = r.u(at + 32, 2);
    const std::string_view record = r.span(at + 46, name_len);
    // Zip64 sizes and offset, in this order, for the fields that overflowed.
    std::uint64_t e = at + 46 + name_len;
    const std::uint64_t e_end = e + extra_len;
    r.span(e, extra_len);
    while (e + 4 <= e_end) {
      const std::uint64_t id = r.u(e, 2), len = r.u(e + 2, 2);
      if (e + 4 + len > e_end) r.fail("record " + escaped(record) + " has a bad extra field");
      if (id == 1) {
        std::uint64_t p = e + 4;
        auto take = [&](std::uint64_t& field) {
          if (field != 0xffffffff) return;
          if (p + 8 > e + 4 + len) r.fail("record " + escaped(record) + " has a short zip64 field");
          field = r.u(p, 8);
          p += 8;
        };
        take(usize);
        take(csize);
        take(local);
      }
      e += 4 + len;
    }
    if (method != 0 && method != 8)
      r.fail("record " + escaped(record) + " uses compression method " + std::to_string(method));
    if (flags & 1) r.fail("record " + escaped(record) + " is encrypted");
    if (method == 0 && csize != usize)
      r.fail("record " + escaped(record) + " has stored size " + std::to_string(csize) + " != " + std::to_string(usize));
    if (r.u(local, 4) != kLocal) r.fail("record " + escaped(record) + " has no local header where the directory says");
    const std::uint64_t lname = r.u(local + 26, 2), lextra = r.u(local + 28, 2);
    if (r.span(local + 30, lname) != record) r.fail("record " + escaped(record) + ": local and central names differ");
    const std::string_view data = r.span(local + 30 + lname + lextra, csize);
    std::uint32_t found = 0;
    if (method == 8 ? !inflated_crc(data, usize, found) : (found = crc32(data), false))
      r.fail("record " + escaped(record) + " does not inflate to its size");
    if (found != crc) r.fail("record " + escaped(record) + " fails its CRC-32 check");
    at += 46 + name_len + extra_len + comment_len;
    if (at > dir_at + dir_size) r.fail("central directory entries overrun the directory");
  }
  return int(entries);
}

int verify_zip_file(const std::string& path) {
  return verify_zip(read_file_bytes(path, kMaxArchiveBytes), path);
}

}  // namespace ptnet
