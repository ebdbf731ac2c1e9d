// ptnet/io.hpp: small file helpers shared by every stage.
//
//   ptnet::AtomicFile out("data.h5", /*force=*/false);  // refuses to clobber
//   write_everything(out.temp_path());
//   out.commit();                                       // rename into place
//
// Outputs are written to a temporary file `.NAME.tmpPID` beside the target and
// renamed when complete, so a failed run never leaves a half-written file.
// The one place where outputs are guarded (docs/formats.md, "Outputs"):
// - without force an existing target is an error;
// - with or without force, a target that is not a regular file (a folder,
//   FIFO, socket or device) is never replaced;
// - a target that is the same file (device and inode) as an input of this
//   run (note_input) is never replaced;
// - on SIGINT, SIGTERM or SIGHUP the live temporary files are removed before
//   the process dies; temporary files of the same target left by dead
//   processes (kill -9) are removed by the next AtomicFile of that target.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

// Largest text input (BVH, CSV, JSON) read whole into memory.
inline constexpr std::uint64_t kMaxTextFileBytes = std::uint64_t(1) << 30;  // 1 GiB

// An input file open for reading. Only a regular file (symbolic links
// followed) is one: anything else is an Error naming the path ("x.csv: is a
// FIFO, expected a regular file", "is a folder, expected a file"), decided
// on the opened file itself and without blocking (a FIFO never waits for a
// writer, a device such as /dev/zero is never read). The readers of user
// files open them through it; HDF5 files (the dataset reader checks them
// itself) and LibTorch's own loads do not.
class InputFile {
 public:
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  std::uint64_t size() const { return size_; }
  // Up to `n` bytes into `out`; fewer only at the end of the file. Throws
  // Error (kind io) on a read error.
  std::size_t read(char* out, std::size_t n);

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

// Reads a whole regular file (InputFile); throws Error naming the file when
// it cannot, when it is larger than `max_bytes` or than the available memory,
// and when it is not UTF-8 text (utf8_invalid_at, strings.hpp): "FILE:LINE:
// expected UTF-8 text, found byte 0xE9 ...", before the caller sees any of it.
std::string read_text_file(const std::string& path, std::uint64_t max_bytes = kMaxTextFileBytes);
// The same bytes, not checked as text (archives, digests of files).
std::string read_file_bytes(const std::string& path, std::uint64_t max_bytes = kMaxTextFileBytes);

// A file named in column `column` of a list's row (a clips or trials CSV:
// `list`, line `line`), relative to `folder` as the filesystem resolves it
// ("link/../x.trc" through the link, never normalised as text; absolute
// names as they are): checked as InputFile will open it (a FIFO, a
// folder, a device refused), before any work, and noted as an input
// (note_input); else Error (its kind) "t.csv:3: marker_map 'x.map': no such
// file" with `hint` appended. "" for an empty name.
std::string listed_input(const std::string& list, long line, const std::string& column, const std::string& folder,
                         const std::string& name, const std::string& hint = "");

// What a file of stat mode `mode` is, for a message: "a folder", "a FIFO",
// "a socket", "a character device", "a block device", "a regular file".
const char* file_kind(unsigned mode);


// Records `path` (device and inode) as an input of this run (this process):
// no output may replace it afterwards. Readers of user data call it
// (datasets, .npy, CSV, BVH, the model a transfer loads); read_text_file
// alone does not (train --resume rewrites the config.json it read).
void note_input(const std::string& path);

// The one wording of an output that exists: Error (kind exists) "PATH:
// exists; pass force to overwrite", or "... overwrite or ALTERNATIVE" (a
// model folder: "resume to continue").
Error exists_error(const std::string& path, const std::string& alternative = "");

// True if folder `path` exists, false if nothing does; throws Error
// "PATH: exists and is not a folder" otherwise.
bool existing_folder(const std::string& path);

// Throws Error if `path` exists and `force` is false, if it exists and is not
// a regular file, if it is an input of this run, or if its folder is missing
// or not writable.
void check_output_path(const std::string& path, bool force);

// An output file's name says what it holds: Error "w.trc: expected a .h5 or
// .hdf5 file name (an HDF5 dataset is written), found '.trc'" unless `path`
// ends in one of `extensions` (".h5"; any case). Every writer of a file of
// one format checks it before its work (check_dataset_output in data.hpp,
// check_bvh_output in motion.hpp, figures, CSV, state dicts).
void check_output_name(const std::string& path, std::initializer_list<const char*> extensions,
                       const std::string& written);

// The same for an output folder (a model or report folder): an existing
// non-folder is an error; an existing non-empty folder needs `force`.
void check_output_folder(const std::string& path, bool force);

// Creates folder `path` and its missing parents; throws Error (kind io)
// "PATH: cannot create folder: REASON".
void make_folder(const std::string& path);

// The outputs `files` of a run to be written into folder `dir` (which may
// not exist yet), before the run: `dir` is no file (existing_folder) and
// each file as check_output_path has it (never a folder, FIFO or device, nor
// an input of this run; `force` if it exists).
void check_outputs_in_folder(const std::string& dir, const std::vector<std::string>& files, bool force);

class AtomicFile {
 public:
  AtomicFile(std::string path, bool force);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temp_path() const { return temp_; }
  const std::string& path() const { return path_; }
  // Renames the temporary file onto path() (checked again: still not an
  // input, still a regular file or absent). Inside a CommitGroup the rename
  // waits for the group's commit().
  void commit();

 private:
  std::string path_, temp_;
  int slot_ = -1;  // signal-cleanup slot
  bool committed_ = false;
};

// Several outputs that appear together or not at all (a report folder):
// while a group is alive on this thread, AtomicFile::commit() hands its
// temporary file to the group; group.commit() renames them all; a group
// destroyed uncommitted (an exception) removes them.
class CommitGroup {
 public:
  CommitGroup();
  ~CommitGroup();
  CommitGroup(const CommitGroup&) = delete;
  CommitGroup& operator=(const CommitGroup&) = delete;
  void commit();

 private:
  friend class AtomicFile;
  struct Pending {
    std::string temp, path;
    int slot;
  };
  std::vector<Pending> pending_;
  CommitGroup* outer_;
};

// Writes `text` to `path` atomically (see AtomicFile).
void write_text_file(const std::string& path, const std::string& text, bool force);

// How a numeric table is written: an OpenSim storage file (.mot, .sto) or CSV.
enum class TableFormat { mot, csv };
inline constexpr TableFormat kTableFormats[] = {TableFormat::mot, TableFormat::csv};
TableFormat parse_table_format(const std::string& text);  // "mot|csv"; throws Error
const char* table_format_name(TableFormat format);         // "mot", "csv": also the extension

// A numeric table, by the extension of `path`: an OpenSim storage file
// (.mot or .sto: the file's stem, version=1, nRows, nColumns, inDegrees=no,
// `note` as one header line when not empty, endheader, then tab-separated
// rows) or CSV (.csv, the note left out); 9 significant digits, NaN as
// "nan". Written atomically; refuses to overwrite unless `force`; Error
// "PATH: expected a .mot, .sto or .csv file name" for another extension.
// rows: [N][columns.size()].
void write_table_file(const std::string& path, const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& rows, const std::string& note, bool force);

// A table as write_table_file writes it (and OpenSim writes storage files),
// read back row by row: by the extension of `path` as write_table_file has
// it, an OpenSim storage file (a header ending in "endheader", then a line
// of column names and one row of numbers per line, tab- or space-separated)
// or CSV (names, then rows; no quoted fields). The file is read whole
// (read_text_file: UTF-8, its size against the memory available) and split
// by LineReader (strings.hpp: a byte-order mark, CRLF, line numbers); only
// the values asked for are parsed, so its memory is the file and what the
// caller keeps (rows_left() bounds what it reserves). Blank lines are
// skipped; a row with another number of fields than there are columns is an
// Error "FILE:LINE: expected 19 values (one per column), found 18".
//   ptnet::TableReader t("walk_grf.mot");
//   const int vy = t.column("ground_force_vy");   // -1: none
//   for (std::vector<double> v; t.next({0, vy}, v);) use(v[0], v[1]);
class TableReader {
 public:
  explicit TableReader(const std::string& path);
  // `text` (not copied) must outlive the reader; `source` names it in errors.
  TableReader(std::string_view text, std::string source, TableFormat format);
  TableReader(const TableReader&) = delete;
  TableReader& operator=(const TableReader&) = delete;
  const std::vector<std::string>& columns() const { return columns_; }
  // Its index, -1 when absent; Error "FILE: column 'x' twice (columns 2
  // and 8) ..." when two columns have the name (a file's other repeated
  // names are no matter while no reader asks for them).
  int column(const std::string& name) const;
  // The next row's values of the columns `use` (indices into columns()), in
  // that order, into `values`: finite numbers, else Error "FILE:LINE:
  // expected a number in column NAME, found 'abc'"; false after the last row.
  bool next(const std::vector<int>& use, std::vector<double>& values);
  // Rows not yet read, at most (lines left, blank ones counted).
  std::size_t rows_left() const { return lines_.lines_left(); }
  long line() const { return lines_.number(); }
  const std::string& source() const { return source_; }

 private:
  void read_names();
  TableFormat format_;  // first: a name of another format is refused before the file is opened
  std::string source_;
  std::string text_;    // the file's text (empty when the text was given)
  LineReader lines_;    // over text_ or the text given
  std::vector<std::string> columns_;
  std::vector<std::string_view> fields_;
};

// The most threads any option may ask for: 4 x the hardware threads (at
// least 4). More only adds scheduling overhead and memory.
int max_threads();

// Throws Error "FILE: WHAT needs 12 GB, more than the 3.1 GB of available
// memory" when `bytes` exceed the available memory.
void check_memory(std::uint64_t bytes, const std::string& file, const std::string& what);
// a * b, or Error "FILE: WHAT overflows" when it does not fit in 64 bits.
std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b, const std::string& file, const std::string& what);
// "512 B", "3.1 MB", "12 GB".
std::string bytes_text(std::uint64_t bytes);

}  // namespace ptnet
