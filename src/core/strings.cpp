// Text helpers (ptnet/strings.hpp).
#include "ptnet/strings.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/io_internal.hpp"
#include "ptnet/error.hpp"

namespace ptnet {
namespace {
bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
}  // namespace

std::string_view trim_view(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && blank(s[b])) ++b;
  while (e > b && blank(s[e - 1])) --e;
  return s.substr(b, e - b);
}

std::string trim(std::string_view s) { return std::string(trim_view(s)); }

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

void split_views(std::string_view text, char sep, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t begin = 0;
  for (std::size_t i = 0; i <= text.size(); ++i)
    if (i == text.size() || text[i] == sep) {
      out.push_back(trim_view(text.substr(begin, i - begin)));
      begin = i + 1;
    }
}

std::vector<std::string> split(std::string_view text, char sep) {
  std::vector<std::string_view> views;
  split_views(text, sep, views);
  return std::vector<std::string>(views.begin(), views.end());
}

std::vector<std::string> split_list(std::string_view text) {
  std::vector<std::string> out;
  for (std::string& item : split(text, ','))
    if (!item.empty()) out.push_back(std::move(item));
  return out;
}

void split_blanks(std::string_view text, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && blank(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !blank(text[i])) ++i;
    if (i > start) out.push_back(text.substr(start, i - start));
  }
}

std::vector<std::string> split_blanks(std::string_view text) {
  std::vector<std::string_view> views;
  split_blanks(text, views);
  return std::vector<std::string>(views.begin(), views.end());
}

std::string join(const std::vector<std::string>& items, std::string_view sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += sep;
    out += items[i];
  }
  return out;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

bool parse_number(std::string_view text, double& value) {
  const std::string t = trim(text);
  if (t.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || !std::isfinite(v)) return false;
  value = v;
  return true;
}

bool parse_integer(std::string_view text, std::int64_t& value) {
  const std::string t = trim(text);
  std::int64_t v = 0;
  const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), v);  // digits, a leading '-'
  if (t.empty() || error != std::errc() || end != t.data() + t.size()) return false;
  value = v;
  return true;
}

bool parse_integer(std::string_view text, std::int64_t lo, std::int64_t hi, std::int64_t& value) {
  std::int64_t v = 0;
  if (!parse_integer(text, v) || v < lo || v > hi) return false;
  value = v;
  return true;
}

std::string one_line(std::string_view text) {
  std::string out;
  for (unsigned char c : text) {
    if (c == '\n' || c == '\r') {
      if (!out.empty() && out.back() != ' ') out += "; ";
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += char(c);
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out;
}

std::string name_problem(std::string_view name) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return "is '.' or '..'";
  if (name.find('/') != std::string_view::npos) return "holds '/'";
  for (unsigned char c : name)
    if (c < 0x20 || c == 0x7f) return "holds a control byte";
  if (utf8_invalid_at(name) != std::string::npos) return "is not UTF-8";
  if (name.size() > kMaxNameBytes) return "is longer than " + std::to_string(kMaxNameBytes) + " bytes";
  return "";
}

std::size_t utf8_invalid_at(std::string_view text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    // The lead byte gives the length and the range of the second byte
    // (which excludes overlong forms, surrogates and values past U+10FFFF).
    int len = 0;
    unsigned char lo = 0x80, hi = 0xbf;
    if (c >= 0xc2 && c <= 0xdf) len = 2;
    else if (c == 0xe0) len = 3, lo = 0xa0;
    else if (c == 0xed) len = 3, hi = 0x9f;
    else if (c >= 0xe1 && c <= 0xef) len = 3;
    else if (c == 0xf0) len = 4, lo = 0x90;
    else if (c >= 0xf1 && c <= 0xf3) len = 4;
    else if (c == 0xf4) len = 4, hi = 0x8f;
    else return i;
    if (i + std::size_t(len) > n || s[i + 1] < lo || s[i + 1] > hi) return i;
    for (int k = 2; k < len; ++k)
      if (s[i + std::size_t(k)] < 0x80 || s[i + std::size_t(k)] > 0xbf) return i;
    i += std::size_t(len);
  }
  return std::string::npos;
}

void check_utf8(std::string_view text, const std::string& source, long first_line) {
  const std::size_t at = utf8_invalid_at(text);
  if (at == std::string::npos) return;
  long line = first_line;
  for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n';
  char byte[8];
  std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[at]));
  throw Error::at(source, line, "UTF-8 text",
                  std::string("byte ") + byte + " (Latin-1 or Windows-1252? save the file as UTF-8)");
}

LineReader::LineReader(std::string_view text) : text_(text) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const std::size_t nl = text_.find('\n', pos_);
  const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
  ++number_;
  return true;
}

std::size_t LineReader::lines_left() const {
  if (pos_ >= text_.size()) return 0;
  std::size_t n = 0;
  const char* p = text_.data() + pos_;
  const char* const end = text_.data() + text_.size();
  while (const void* nl = std::memchr(p, '\n', std::size_t(end - p))) {
    ++n;
    p = static_cast<const char*>(nl) + 1;
  }
  return n + (p < end ? 1 : 0);
}

std::string first_repeat(const std::vector<std::string>& items) {
  for (std::size_t i = 0; i < items.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (items[j] == items[i]) return items[i];
  return "";
}

}  // namespace ptnet
