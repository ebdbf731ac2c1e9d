// ptnet/strings.hpp: the small text helpers every stage shares (the one
// definition of each; no stage keeps its own copy).
//
//   ptnet::split("female, 165 ,60", ',')     // {"female", "165", "60"}
//   ptnet::split_list("1, 2,,3")              // {"1", "2", "3"} (empty items dropped)
//   ptnet::lower(ptnet::trim("  Male "))      // "male"
//   double v; ptnet::parse_number("1e3", v)  // true, v = 1000
//   std::int64_t n; ptnet::parse_integer("1e3", n)  // false: digits only
//   ptnet::name_problem("../x")               // "holds '/'": not a file name
//   ptnet::utf8_invalid_at("caf\xe9")         // 3: Latin-1, not UTF-8
//   ptnet::LineReader lines(text);            // BOM skipped, CRLF read as LF
//   for (std::string_view l; lines.next(l);) f(l, lines.number());
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ptnet {

// Without leading and trailing blanks (space, tab, CR, LF).
std::string trim(std::string_view s);
// The same as a view into `s` (no copy: parsers of large files).
std::string_view trim_view(std::string_view s);
// ASCII lower case.
std::string lower(std::string s);
// Fields between `sep`, each trimmed; "" gives {""}, "a," gives {"a", ""}.
std::vector<std::string> split(std::string_view text, char sep = ',');
// A comma-separated list as typed on a command line: items trimmed, empty ones dropped.
std::vector<std::string> split_list(std::string_view text);
// The words of a line between runs of blanks (space, tab, CR, LF).
std::vector<std::string> split_blanks(std::string_view text);
// The same as views into `text`, into `out` (cleared; its capacity reused
// line after line by parsers of large files).
void split_blanks(std::string_view text, std::vector<std::string_view>& out);
// Fields between `sep` as views into `text`, each trimmed, into `out`
// (cleared): split()'s rule without copies.
void split_views(std::string_view text, char sep, std::vector<std::string_view>& out);
// The items joined with `sep`.
std::string join(const std::vector<std::string>& items, std::string_view sep = ",");
bool ends_with(std::string_view s, std::string_view suffix);
// A finite number that is the whole (trimmed) text; false otherwise (value unchanged).
bool parse_number(std::string_view text, double& value);
// A whole number in decimal digits, an optional '-' first, that is the whole
// (trimmed) text and fits in 64 bits: "0x10", "1.0", "3L", "+1" and
// "4294967298" for an int are not; false otherwise (value unchanged).
bool parse_integer(std::string_view text, std::int64_t& value);
// The same within [lo, hi].
bool parse_integer(std::string_view text, std::int64_t lo, std::int64_t hi, std::int64_t& value);
// The first item equal to an earlier one, "" when all differ: a list
// option given twice the same value (compare normalised forms, as the
// option reads them: lower case, a speed's label). Lists are short.
std::string first_repeat(const std::vector<std::string>& items);
// The longest name a user gives that becomes a file name (a trial, a
// sequence written as NAME.mot): room for a suffix within the 255 bytes of
// a file name.
inline constexpr std::size_t kMaxNameBytes = 200;
// Why `name` cannot be one file name inside an output folder (a trial's,
// a sequence's NAME.mot), "" when it can: "is empty", "holds '/'", "is '.'
// or '..'", "holds a control byte", "is not UTF-8", "is longer than 200
// bytes". The one rule of every user string that becomes a file name
// (trial names, sequence names, their motion and body ids).
std::string name_problem(std::string_view name);

// The offset of the first byte of `text` that is not part of valid UTF-8
// (overlong forms, surrogates and code points above U+10FFFF are not), or
// std::string::npos when it all is.
std::size_t utf8_invalid_at(std::string_view text);
// Every reader of text files checks it before using any (read_text_file,
// ptnet/io.hpp: "FILE:LINE: expected UTF-8 text, found byte 0xE9 ...").

// The lines of a text, numbered from 1, for every reader of text files: a
// UTF-8 byte-order mark at the start is skipped, a line ends at LF and a CR
// before it is dropped (LF and CRLF files read alike). Views into `text`,
// which must outlive the reader.
class LineReader {
 public:
  explicit LineReader(std::string_view text);
  // The next line (without its end) in `line`; false at the end of the text.
  bool next(std::string_view& line);
  // The number of the line last returned (0 before the first).
  long number() const { return number_; }
  // Lines not yet returned (a line without its LF at the end counts): a
  // bound for what a parser reserves.
  std::size_t lines_left() const;

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  long number_ = 0;
};

// A message as one line (how the CLI and the Python module show an error):
// line breaks become "; ", other control bytes are escaped (\x1b), trailing
// blanks and semicolons dropped.
std::string one_line(std::string_view text);

}  // namespace ptnet
