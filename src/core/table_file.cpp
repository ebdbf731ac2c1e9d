// Numeric tables as OpenSim storage files or CSV (ptnet/io.hpp): the writer
// and its reader.
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

TableFormat parse_table_format(const std::string& text) {
  for (TableFormat f : kTableFormats)
    if (text == table_format_name(f)) return f;
  throw Error("table format: expected mot or csv, found " + escaped(text));
}

const char* table_format_name(TableFormat format) { return format == TableFormat::csv ? "csv" : "mot"; }

namespace {

// The format a file name asks for: .mot or .sto (OpenSim storage), .csv;
// Error "PATH: expected a .mot, .sto or .csv file name" for another.
TableFormat table_format_of(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".mot" || ext == ".sto") return TableFormat::mot;
  if (ext == ".csv") return TableFormat::csv;
  throw Error::in(path, "expected a .mot, .sto or .csv file name");
}

}  // namespace

void write_table_file(const std::string& path, const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& rows, const std::string& note, bool force) {
  const bool csv = table_format_of(path) == TableFormat::csv;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].size() != columns.size())
      throw Error::in(path, "row " + std::to_string(i) + ": expected " + std::to_string(columns.size()) +
                                " values, found " + std::to_string(rows[i].size()));
  const char sep = csv ? ',' : '\t';
  std::ostringstream o;
  o << std::setprecision(9);
  if (!csv) {
    o << std::filesystem::path(path).stem().string() << "\nversion=1\nnRows=" << rows.size()
      << "\nnColumns=" << columns.size() << "\ninDegrees=no\n";
    if (!note.empty()) o << note << "\n";
    o << "endheader\n";
  }
  o << join(columns, std::string(1, sep)) << "\n";
  for (const auto& row : rows) {
    for (std::size_t j = 0; j < row.size(); ++j) o << (j ? std::string(1, sep) : "") << row[j];
    o << "\n";
  }
  write_text_file(path, o.str(), force);
}

// ------------------------------------------------------------ reading

namespace {

// The fields of a line: between runs of blanks (storage) or commas (CSV),
// each trimmed of blanks.
void split_fields(std::string_view line, TableFormat format, std::vector<std::string_view>& out) {
  if (format == TableFormat::mot) return split_blanks(line, out);
  split_views(line, ',', out);
}

bool blank_line(std::string_view line) { return trim_view(line).empty(); }

}  // namespace

TableReader::TableReader(const std::string& path)
    : format_(table_format_of(path)), source_(path), text_(read_text_file(path)), lines_(text_) {
  read_names();
}

TableReader::TableReader(std::string_view text, std::string source, TableFormat format)
    : format_(format), source_(std::move(source)), lines_(text) {
  read_names();
}

void TableReader::read_names() {
  std::string_view line;
  if (format_ == TableFormat::mot) {
    bool header = true;
    while (header && lines_.next(line)) header = trim(line) != "endheader";
    if (header) throw Error::in(source(), "expected an OpenSim storage header ending in 'endheader', found none");
  }
  while (lines_.next(line))
    if (!blank_line(line)) {
      split_fields(line, format_, fields_);
      for (std::string_view f : fields_) columns_.emplace_back(f);
      return;
    }
  throw Error::in(source(), std::string("no column names") +
                                (format_ == TableFormat::mot ? " after 'endheader'" : ""));
}

int TableReader::column(const std::string& name) const {
  int found = -1;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (columns_[c] != name) continue;
    if (found >= 0)
      throw Error::in(source(), "column " + escaped(name, 60) + " twice (columns " + std::to_string(found + 1) +
                                    " and " + std::to_string(c + 1) + "): which one is meant?");
    found = int(c);
  }
  return found;
}

bool TableReader::next(const std::vector<int>& use, std::vector<double>& values) {
  std::string_view text;
  do {
    if (!lines_.next(text)) return false;
  } while (blank_line(text));
  split_fields(text, format_, fields_);
  if (fields_.size() != columns_.size())
    throw Error::at(source(), line(), std::to_string(columns_.size()) + " values (one per column)",
                    std::to_string(fields_.size()));
  values.resize(use.size());
  for (std::size_t k = 0; k < use.size(); ++k) {
    const std::size_t c = std::size_t(use[k]);
    if (!parse_number(fields_.at(c), values[k]))
      throw Error::at(source(), line(), "a number in column " + escaped(columns_[c], 60, false), escaped(fields_[c]));
  }
  return true;
}

}  // namespace ptnet
