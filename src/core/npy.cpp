// Minimal .npy (NumPy format 1.0-3.0) float32 reader and writer.
#include "ptnet/npy.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "core/npy_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

std::string shape_text(const std::vector<std::int64_t>& shape) {
  std::string s = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + "]";
}

// Value text of `key` in a Python dict literal header ("'descr': '<f4', ...").
std::string dict_value(const std::string& header, const std::string& key, const std::string& path) {
  auto k = header.find("'" + key + "'");
  if (k == std::string::npos) throw Error::in(path, "npy header has no '" + key + "'");
  auto colon = header.find(':', k);
  if (colon == std::string::npos) throw Error::in(path, "npy header: expected ':' after '" + key + "'");
  std::size_t b = header.find_first_not_of(' ', colon + 1);
  if (b == std::string::npos) throw Error::in(path, "npy header truncated");
  std::size_t e;
  if (header[b] == '(') e = header.find(')', b) + 1;
  else if (header[b] == '\'') e = header.find('\'', b + 1) + 1;
  else e = header.find_first_of(",}", b);
  if (e == std::string::npos || e == 0) throw Error::in(path, "npy header: bad value for '" + key + "'");
  return header.substr(b, e - b);
}

// The data bytes the header's shape needs (and its element count).
std::uint64_t data_bytes(const NpyHeader& h, const std::string& path, std::uint64_t& count) {
  count = 1;
  for (std::int64_t v : h.shape) count = checked_mul(count, std::uint64_t(v), path, "npy header: the shape's element count");
  return checked_mul(count, sizeof(float), path, "npy header: the shape's byte count");
}

}  // namespace

// The header first, then the data straight into the array: the file is
// never held twice, and only what the shape announces (checked against the
// file's size and the available memory) is read. A regular file only
// (InputFile): /dev/zero or a FIFO is refused at once.
NpyArray read_npy(const std::string& path) {
  InputFile in(path);
  note_input(path);
  std::string head(12, '\0');
  head.resize(in.read(head.data(), head.size()));
  const std::size_t header_size = npy_header_size(head, path);
  if (header_size > kMaxNpyHeaderBytes)
    throw Error::in(path, "npy header of " + bytes_text(header_size) + ", more than " + bytes_text(kMaxNpyHeaderBytes));
  if (header_size > head.size()) {
    const std::size_t had = head.size();
    head.resize(header_size);
    if (in.read(head.data() + had, header_size - had) != header_size - had) throw Error::in(path, "npy header truncated");
  }
  NpyHeader h = parse_npy_header(head, path);
  std::uint64_t count = 0;
  const std::uint64_t need = data_bytes(h, path, count);
  const auto wrong_size = [&](const std::string& found) {
    return Error::in(path, "expected " + std::to_string(need) + " data bytes for shape " + shape_text(h.shape) +
                               ", found " + found);
  };
  if (in.size() - h.data_offset != need) throw wrong_size(std::to_string(in.size() - h.data_offset));
  if (need > kMaxNpyBytes)
    throw Error::in(path, bytes_text(need) + " of data, more than the " + bytes_text(kMaxNpyBytes) + " a .npy file may have");
  check_memory(need, path, "reading the array");
  NpyArray a;
  a.shape = std::move(h.shape);
  a.data.resize(std::size_t(count));
  const std::size_t got = in.read(reinterpret_cast<char*>(a.data.data()), std::size_t(need));  // little-endian host
  if (got != need) throw wrong_size(std::to_string(got) + " (it shrank while read)");
  char more = 0;
  if (in.read(&more, 1) != 0) throw wrong_size("more");
  return a;
}

std::size_t npy_header_size(const std::string& bytes, const std::string& path) {
  if (bytes.size() < 10 || std::memcmp(bytes.data(), "\x93NUMPY", 6) != 0)
    throw Error::in(path, "not a .npy file (expected the \\x93NUMPY magic)");
  const int major = static_cast<unsigned char>(bytes[6]);
  if (major == 1)
    return 10 + (std::size_t(static_cast<unsigned char>(bytes[8])) |
                 std::size_t(static_cast<unsigned char>(bytes[9])) << 8);
  if (major != 2 && major != 3) throw Error::in(path, "unsupported npy version " + std::to_string(major));
  if (bytes.size() < 12) throw Error::in(path, "npy header truncated");
  std::size_t header_len = 0;
  for (int i = 0; i < 4; ++i) header_len |= std::size_t(static_cast<unsigned char>(bytes[8 + i])) << (8 * i);
  return 12 + header_len;
}

NpyHeader parse_npy_header(const std::string& bytes, const std::string& path) {
  const std::size_t end = npy_header_size(bytes, path);
  const std::size_t offset = static_cast<unsigned char>(bytes[6]) == 1 ? 10 : 12;
  if (bytes.size() < end) throw Error::in(path, "npy header truncated");
  const std::string header = bytes.substr(offset, end - offset);
  const std::string descr = dict_value(header, "descr", path);
  if (descr != "'<f4'" && descr != "'|f4'")
    throw Error::in(path, "expected dtype float32 ('<f4'), found " + escaped(descr, 40, false));
  if (dict_value(header, "fortran_order", path) != "False")
    throw Error::in(path, "Fortran-order arrays are not supported (save with C order)");
  std::string shape = dict_value(header, "shape", path);
  if (shape.size() < 2 || shape.front() != '(' || shape.back() != ')')
    throw Error::in(path, "npy header: bad shape " + escaped(shape));
  NpyHeader h;
  h.data_offset = end;
  const std::vector<std::string> items = split(std::string_view(shape).substr(1, shape.size() - 2), ',');
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].empty() && i + 1 == items.size()) continue;  // "(3,)" and "()"
    std::int64_t v = 0;
    if (!parse_integer(items[i], 0, INT64_MAX, v))  // whole decimal numbers: not 80.9, not 3L
      throw Error::in(path, "npy header: bad shape " + escaped(shape));
    h.shape.push_back(v);
  }
  return h;
}

NpyArray parse_npy(const std::string& bytes, const std::string& path) {
  NpyHeader h = parse_npy_header(bytes, path);
  std::uint64_t count = 0;
  const std::uint64_t need = data_bytes(h, path, count);
  NpyArray a;
  a.shape = std::move(h.shape);
  const std::size_t data_at = h.data_offset;
  if (std::uint64_t(bytes.size() - data_at) != need)
    throw Error::in(path, "expected " + std::to_string(need) + " data bytes for shape " +
                              shape_text(a.shape) + ", found " + std::to_string(bytes.size() - data_at));
  a.data.resize(std::size_t(count));
  if (count) std::memcpy(a.data.data(), bytes.data() + data_at, need);  // little-endian host
  return a;
}

void write_npy(const std::string& path, const NpyArray& a, bool force) {
  std::int64_t count = 1;
  for (auto v : a.shape) count *= v;
  if (std::size_t(count) != a.data.size()) throw Error::in(path, "npy: shape does not match the data size");
  std::string shape = "(";
  for (std::size_t i = 0; i < a.shape.size(); ++i) shape += std::to_string(a.shape[i]) + ", ";
  if (a.shape.size() > 1) shape.erase(shape.size() - 2);
  else if (a.shape.size() == 1) shape.erase(shape.size() - 1);
  shape += ")";
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
  std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  AtomicFile out(path, force);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    if (!f) throw Error::in(path, "cannot write", ErrorKind::io);
    f.write("\x93NUMPY\x01\x00", 8);
    const char len[2] = {char(header.size() & 0xff), char(header.size() >> 8)};
    f.write(len, 2);
    f << header;
    f.write(reinterpret_cast<const char*>(a.data.data()), std::streamsize(a.data.size() * sizeof(float)));
    f.flush();
    if (!f) throw Error::in(path, "write failed (disk full?)", ErrorKind::io);
  }
  out.commit();
}

PressureSequence read_npy_sequence(const std::string& path, const MatSpec& mat, double fps) {
  NpyArray a = read_npy(path);
  if (a.shape.size() != 3 || a.shape[1] != mat.rows || a.shape[2] != mat.cols)
    throw Error::in(path, "expected shape [T, " + std::to_string(mat.rows) + ", " +
                              std::to_string(mat.cols) + "], found " + shape_text(a.shape));
  PressureSequence s;
  s.mat = mat;
  s.fps = fps;
  s.kpa = std::move(a.data);
  check_pressure(s.kpa.data(), s.kpa.size(), mat.cells(), path, "");
  return s;
}

void write_npy_sequence(const std::string& path, const PressureSequence& seq, bool force) {
  NpyArray a;
  a.shape = {seq.frames(), seq.mat.rows, seq.mat.cols};
  a.data = seq.kpa;
  write_npy(path, a, force);
}

}  // namespace ptnet
