// RFC 4180 CSV reader (core/csv.hpp): a character state machine, linear in
// the text size.
#include "core/csv.hpp"

#include <algorithm>
#include <cctype>
#include <unordered_map>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

// What follows position `at` on its line, for a message.
std::string rest_of_line(std::string_view text, std::size_t at) {
  const std::size_t end = text.find_first_of("\r\n", at);
  return escaped(text.substr(at, std::min<std::size_t>(end == std::string_view::npos ? text.size() - at : end - at, 20)));
}

}  // namespace

int CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return int(i);
  return -1;
}

int CsvTable::required(std::string_view name, const std::string& columns) const {
  const int i = column(name);
  if (i >= 0) return i;
  std::string found;
  for (std::size_t k = 0; k < header.size(); ++k) found += (k ? "," : "") + header[k];
  throw Error::at(source, header_line, "a header with column " + std::string(name) + " (" + columns + ")",
                  escaped(found, 60));
}

const std::string& CsvTable::field(const CsvRow& row, int index) {
  static const std::string empty;
  return index < 0 ? empty : row.fields[std::size_t(index)];
}

namespace {

// The quoted field at text[i] ('"'): its text, "" for a doubled quote;
// `i` moves past it and the blanks after, `line` past its line ends.
std::string quoted_field(std::string_view text, std::size_t& i, long& line, const std::string& source) {
  const std::size_t n = text.size();
  const long open_line = line;
  std::string field;
  ++i;
  for (;;) {
    if (i >= n) throw Error::at(source, open_line, "a closing quote", "end of file");
    const char c = text[i++];
    if (c == '"') {
      if (i < n && text[i] == '"') {
        field += '"';
        ++i;
      } else {
        break;
      }
    } else {
      if (c == '\n') ++line;
      field += c;
    }
  }
  while (i < n && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r')) ++i;
  if (i < n && text[i] != ',' && text[i] != '\n')
    throw Error::at(source, line, "a comma or line end after a closing quote", rest_of_line(text, i));
  return field;
}

// The unquoted field at text[i], trimmed; `i` moves to the comma or line end.
std::string plain_field(std::string_view text, std::size_t& i, long line, const std::string& source) {
  const std::size_t b = i, n = text.size();
  while (i < n && text[i] != ',' && text[i] != '\n') {
    if (text[i] == '"') throw Error::at(source, line, "a quote only at the start of a field", rest_of_line(text, b));
    ++i;
  }
  std::string_view raw = text.substr(b, i - b);
  if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
  return trim(raw);
}

// A header names each column once (an empty name aside): a second column
// of one name would be read as the first, or not at all.
void check_header(const CsvTable& t) {
  std::unordered_map<std::string_view, std::size_t> seen;
  for (std::size_t a = 0; a < t.header.size(); ++a) {
    if (t.header[a].empty()) continue;
    const auto [it, fresh] = seen.emplace(t.header[a], a);
    if (!fresh)
      throw Error::at(t.source, t.header_line, "each column named once",
                      escaped(t.header[a], 40) + " as columns " + std::to_string(it->second + 1) + " and " +
                          std::to_string(a + 1));
  }
}

// What the table of `text` holds at most, checked against the memory
// available before it is parsed: a field per comma or line end, a row per
// line end, the fields' text (a short field is held in its string).
void check_table_memory(std::string_view text, const std::string& source) {
  const std::uint64_t lines = std::uint64_t(std::count(text.begin(), text.end(), '\n')) + 1;
  const std::uint64_t fields = std::uint64_t(std::count(text.begin(), text.end(), ',')) + lines;
  check_memory(checked_mul(fields, sizeof(std::string), source, "the CSV's fields") +
                   checked_mul(lines, sizeof(CsvRow), source, "the CSV's rows") + text.size(),
               source, "the CSV's " + std::to_string(fields) + " fields");
}

}  // namespace

CsvTable parse_csv(std::string_view text, const std::string& source) {
  check_table_memory(text, source);
  CsvTable t;
  t.source = source;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::size_t i = 0;
  long line = 1;
  const std::size_t n = text.size();
  while (i < n) {
    // Start of a record: skip blank and comment lines.
    const long first_line = line;
    std::size_t probe = i;
    while (probe < n && (text[probe] == ' ' || text[probe] == '\t' || text[probe] == '\r')) ++probe;
    if (probe == n) break;
    if (text[probe] == '\n' || text[probe] == '#') {
      while (probe < n && text[probe] != '\n') ++probe;
      i = probe + 1;
      ++line;
      continue;
    }
    CsvRow row;
    row.line = first_line;
    row.fields.reserve(t.header.size());  // the rows after the header: exactly
    for (;;) {  // one field per iteration
      while (i < n && (text[i] == ' ' || text[i] == '\t')) ++i;
      std::string field = i < n && text[i] == '"' ? quoted_field(text, i, line, source) : plain_field(text, i, line, source);
      row.fields.push_back(std::move(field));
      if (i < n && text[i] == ',') {
        ++i;
        continue;
      }
      if (i < n) ++i;  // '\n'
      ++line;
      break;
    }
    if (t.header.empty() && t.header_line == 0) {
      for (auto& f : row.fields) t.header.push_back(lower(f));
      t.header_line = row.line;
      check_header(t);
      t.rows.reserve(std::size_t(std::count(text.begin() + std::ptrdiff_t(i), text.end(), '\n')) + 1);
      continue;
    }
    if (row.fields.size() != t.header.size())
      throw Error::at(source, row.line, std::to_string(t.header.size()) + " fields (as the header)",
                      std::to_string(row.fields.size()));
    t.rows.push_back(std::move(row));
  }
  if (t.header_line == 0) throw Error::in(source, "empty CSV file, expected a header line");
  return t;
}

std::string csv_field(const std::string& value) {
  const bool plain = value.find_first_of(",\"\r\n") == std::string::npos &&
                     (value.empty() || (value.front() != ' ' && value.front() != '\t' && value.back() != ' ' &&
                                        value.back() != '\t' && value.front() != '#'));
  if (plain) return value;
  std::string out = "\"";
  for (char c : value) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csv_text_field(const std::string& value) {
  const bool neutralise = !value.empty() && std::string_view("=+-@\t\r'").find(value.front()) != std::string_view::npos;
  return csv_field(neutralise ? "'" + value : value);
}

std::string csv_text_value(const std::string& field) {
  return !field.empty() && field.front() == '\'' ? field.substr(1) : field;
}

CsvTable read_csv(const std::string& path) {
  note_input(path);
  return parse_csv(read_text_file(path), path);
}

}  // namespace ptnet
