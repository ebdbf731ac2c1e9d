// core/csv.hpp: the one CSV reader (RFC 4180) behind every CSV ptnet reads
// (bodies, clips, recordings manifests, metrics.csv), and its fields for
// writing.
//
//   ptnet::CsvTable t = ptnet::read_csv("bodies.csv");
//   const int h = t.column("height_cm");          // -1 if absent
//   for (const auto& row : t.rows) use(row.fields[h], row.line);
//
// Accepted: a UTF-8 byte-order mark, LF or CRLF line ends, quoted fields
// ("female", "a, b", "say ""hi""", line breaks inside quotes), blank lines
// and lines starting with '#' (skipped). Unquoted fields are trimmed of
// spaces and tabs. The first remaining line is the header; its names are
// matched case-insensitively, so columns may come in any order, and each is
// named once ("markers" twice is refused: one would be read, the other not).
// Every row must have as many fields as the header. Errors are one line:
// "bodies.csv:4: expected 4 fields, found 5".
//
// Private to the library (not installed): the stages include it as
// "core/csv.hpp".
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace ptnet {

struct CsvRow {
  std::vector<std::string> fields;
  long line = 0;  // line of the row's first character (1-based)
};

struct CsvTable {
  std::string source;                // file name, for messages
  std::vector<std::string> header;   // lower-case, trimmed
  long header_line = 0;
  std::vector<CsvRow> rows;

  int column(std::string_view name) const;  // index in header, -1 if absent
  // Index of a column that must exist; throws Error
  // "FILE:LINE: expected a header with column NAME (COLUMNS), found 'a,b,c'".
  int required(std::string_view name, const std::string& columns) const;
  // The field of `row` in column `index`, "" for index -1.
  static const std::string& field(const CsvRow& row, int index);
};

// Parses CSV text; `source` names it in messages. An empty text (no header)
// is an error.
CsvTable parse_csv(std::string_view text, const std::string& source);
// A field for writing: quoted (with "" for ") when it holds a comma, quote,
// line break or surrounding blanks; unchanged otherwise.
std::string csv_field(const std::string& value);
// A text field of a CSV that spreadsheets open (metrics.csv): csv_field of
// the value, with a value a spreadsheet would take for a formula (leading
// =, +, -, @, tab or CR) neutralised by a leading ' ("CSV injection"); a
// value that starts with ' gets one more, so that csv_text_value reads
// every value back as it was.
std::string csv_text_field(const std::string& value);
// The value of a field csv_text_field wrote (as parse_csv returns it).
std::string csv_text_value(const std::string& field);

// Reads and parses a file (read_text_file: size limits), noted as an input.
CsvTable read_csv(const std::string& path);

}  // namespace ptnet
