// core/zip_check.hpp: integrity of the zip archives LibTorch writes
// (model.pt, checkpoint.pt). LibTorch's own reader skips the CRC-32 checks,
// so a damaged archive would load; ptnet checks every record first.
//
//   ptnet::verify_zip_file("model/model.pt");   // throws Error naming the file
//
// Checked: the end-of-central-directory record (zip64 too), every central
// directory entry, its local header (same name, inside the file), each
// record's data (stored, or deflated: inflated in pieces) and its CRC-32
// against the directory's.
//
// Private to the library (not installed): the stages include it as
// "core/zip_check.hpp".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace ptnet {

// Largest model or checkpoint archive read (the available memory is checked too).
inline constexpr std::uint64_t kMaxArchiveBytes = std::uint64_t(16) << 30;  // 16 GiB

// CRC-32 (IEEE 802.3, as zip and zlib), continuing from `crc`.
std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0);

// Verifies an archive held in memory; `name` names it in messages:
// "model.pt: damaged archive: record 'archive/data/3' fails its CRC-32 check".
// Returns the number of records.
int verify_zip(std::string_view bytes, const std::string& name);
// Reads the file (size-limited) and verifies it.
int verify_zip_file(const std::string& path);

}  // namespace ptnet
