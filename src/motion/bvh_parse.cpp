// BVH reader: a hand-rolled tokenizer for the HIERARCHY and a line scanner
// with std::from_chars for the MOTION block (no iostreams in the hot loop).
//
// Every malformed input is a one-line ptnet::Error "FILE:LINE: expected X,
// found Y". Accepted: LF or CRLF, tabs or spaces, a UTF-8 byte-order mark,
// any channel order, 0, 3 or 6 channels per joint, `End Site`, blank lines.
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_set>
#include <vector>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {
namespace {

constexpr int kMaxDepth = 512;  // nested joints; deeper is surely not a skeleton

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// A token for messages: unquoted, control bytes escaped, cut to a readable
// length.
std::string shown(std::string_view token) {
  if (token.empty()) return "end of file";
  return escaped(token, 40, /*quotes=*/false);
}

// The first token of a file that is not a BVH file is not echoed: the file
// may be anything (a clips CSV row can name any file).
bool is_bvh_keyword(std::string_view t) {
  for (std::string_view k : {"ROOT", "JOINT", "MOTION", "OFFSET", "CHANNELS", "End", "Site", "{", "}", "Frames:"})
    if (t == k) return true;
  return false;
}

struct Token {
  std::string_view text;  // empty at end of file
  long line = 0;
};

class Lexer {
 public:
  Lexer(std::string_view text, const std::string& source) : text_(text), source_(source) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
  }

  Token next() {
    skip_blank(true);
    Token t{{}, line_};
    std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '\n') ++pos_;
    t.text = text_.substr(start, pos_ - start);
    return t;
  }

  // The rest of the current line, trimmed (used for joint names).
  std::string_view rest_of_line() {
    skip_blank(false);
    std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::size_t stop = pos_;
    while (stop > start && is_space(text_[stop - 1])) --stop;
    return text_.substr(start, stop - start);
  }

  // Moves past the end of the current line; false if other text is on it.
  bool finish_line(Token& extra) {
    skip_blank(false);
    if (pos_ >= text_.size()) return true;
    if (text_[pos_] == '\n') {
      ++pos_;
      ++line_;
      return true;
    }
    extra = next();
    return false;
  }

  [[noreturn]] void fail(long line, const std::string& expected, std::string_view found) const {
    throw Error::at(source_, line, expected, shown(found));
  }

  double number(const char* what) {
    Token t = next();
    double v = 0;
    if (!parse_double(t.text, v)) fail(t.line, std::string("a ") + what, t.text);
    if (!std::isfinite(v)) fail(t.line, std::string("a finite ") + what, t.text);
    return v;
  }

  static bool parse_double(std::string_view s, double& v) {
    if (s.empty()) return false;
    const char* b = s.data();
    const char* e = b + s.size();
    if (*b == '+' && s.size() > 1) ++b;
    auto r = std::from_chars(b, e, v);
    return r.ec == std::errc() && r.ptr == e;
  }

  std::size_t pos() const { return pos_; }
  long line() const { return line_; }
  std::string_view text() const { return text_; }

 private:
  void skip_blank(bool newlines) {
    while (pos_ < text_.size()) {
      char c = text_[pos_];
      if (is_space(c)) {
        ++pos_;
      } else if (c == '\n' && newlines) {
        ++pos_;
        ++line_;
      } else {
        break;
      }
    }
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  long line_ = 1;
};

bool channel_from_name(std::string_view s, Channel& c) {
  static constexpr std::string_view kNames[] = {"Xposition", "Yposition", "Zposition",
                                                "Xrotation", "Yrotation", "Zrotation"};
  for (int i = 0; i < 6; ++i)
    if (s == kNames[i]) {
      c = Channel(i);
      return true;
    }
  return false;
}

class HierarchyParser {
 public:
  HierarchyParser(Lexer& lex, Bvh& bvh) : lex_(lex), bvh_(bvh) {}

  // At the token after ROOT/JOINT (`keyword_line` is its line).
  void joint(int parent, long keyword_line, int depth) {
    if (depth > kMaxDepth) lex_.fail(keyword_line, "at most 512 nested joints", "deeper nesting");
    std::string_view name = lex_.rest_of_line();
    bool brace = false;
    if (!name.empty() && name.back() == '{') {
      brace = true;
      name.remove_suffix(1);
      while (!name.empty() && is_space(name.back())) name.remove_suffix(1);
    }
    if (name.empty()) lex_.fail(keyword_line, "a joint name", brace ? "{" : "end of line");
    if (!names_.insert(std::string(name)).second)
      lex_.fail(keyword_line, "a joint name not used before", std::string(name) + " again");

    const int index = int(bvh_.joints.size());
    bvh_.joints.emplace_back();
    bvh_.joints[index].name = std::string(name);
    bvh_.joints[index].parent = parent;

    Token t;
    if (!brace) {
      t = lex_.next();
      if (t.text != "{") lex_.fail(t.line, "{", t.text);
    }
    t = lex_.next();
    if (t.text != "OFFSET") lex_.fail(t.line, "OFFSET", t.text);
    for (int a = 0; a < 3; ++a) bvh_.joints[index].offset[a] = lex_.number("number (OFFSET)");

    t = lex_.next();
    bvh_.joints[index].first_channel = bvh_.channel_count;
    if (t.text == "CHANNELS") {
      channels(index);
      t = lex_.next();
    }

    for (;; t = lex_.next()) {
      if (t.text == "}") return;
      if (t.text == "JOINT") {
        joint(index, t.line, depth + 1);
      } else if (t.text == "End") {
        Token s = lex_.next();
        if (s.text != "Site") lex_.fail(s.line, "Site (after End)", s.text);
        end_site(index);
      } else {
        lex_.fail(t.line, "JOINT, End Site or }", t.text);
      }
    }
  }

 private:
  // At the token after CHANNELS: the count and the names of joint `index`'s channels.
  void channels(int index) {
    Token n = lex_.next();
    int count = -1;
    auto r = std::from_chars(n.text.data(), n.text.data() + n.text.size(), count);
    if (r.ec != std::errc() || r.ptr != n.text.data() + n.text.size() || (count != 0 && count != 3 && count != 6))
      lex_.fail(n.line, "a channel count of 0, 3 or 6", n.text);
    std::vector<Channel> list;
    for (int i = 0; i < count; ++i) {
      Token c = lex_.next();
      Channel ch;
      if (!channel_from_name(c.text, ch)) lex_.fail(c.line, "a channel name (X|Y|Z + position|rotation)", c.text);
      for (Channel seen : list)
        if (seen == ch) lex_.fail(c.line, "a channel not listed before on this joint", c.text);
      list.push_back(ch);
    }
    bvh_.joints[index].channels = std::move(list);
    bvh_.channel_count += count;
  }

  void end_site(int index) {
    Token t = lex_.next();
    if (t.text != "{") lex_.fail(t.line, "{", t.text);
    t = lex_.next();
    if (t.text != "OFFSET") lex_.fail(t.line, "OFFSET", t.text);
    Eigen::Vector3d offset;
    for (int a = 0; a < 3; ++a) offset[a] = lex_.number("number (OFFSET)");
    t = lex_.next();
    if (t.text != "}") lex_.fail(t.line, "} (closing End Site)", t.text);
    BvhJoint& j = bvh_.joints[index];
    if (!j.has_end_site) {
      j.has_end_site = true;
      j.end_site = offset;
    }
  }

  Lexer& lex_;
  Bvh& bvh_;
  std::unordered_set<std::string> names_;  // joint names so far: linear, not quadratic, in the joint count
};

// Parses one frame value at p (no leading blanks); returns the end of the token.
const char* frame_value(const char* p, const char* end, double& v, bool& ok) {
  const char* b = (*p == '+' && p + 1 < end) ? p + 1 : p;
  auto r = std::from_chars(b, end, v);
  ok = r.ec == std::errc() && (r.ptr == end || is_space(*r.ptr) || *r.ptr == '\n');
  return r.ptr;
}

std::string frame_lines(long frames) {
  return std::to_string(frames) + (frames == 1 ? " frame line" : " frame lines") +
         " (Frames: " + std::to_string(frames) + ")";
}

}  // namespace

int Bvh::find(std::string_view joint_name) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == joint_name) return int(i);
  return -1;
}

namespace {

// The MOTION header after its keyword: "Frames: N" and "Frame Time: S" (into
// bvh.frame_time); the frame count.
long parse_motion_header(Lexer& lex, Bvh& bvh) {
  Token t = lex.next();
  if (t.text != "Frames:") lex.fail(t.line, "Frames:", t.text);
  Token n = lex.next();
  long frames = -1;
  auto r = std::from_chars(n.text.data(), n.text.data() + n.text.size(), frames);
  if (r.ec != std::errc() || r.ptr != n.text.data() + n.text.size() || frames < 1)
    lex.fail(n.line, "a frame count of at least 1", n.text);
  t = lex.next();
  if (t.text != "Frame") lex.fail(t.line, "Frame Time:", t.text);
  t = lex.next();
  if (t.text != "Time:") lex.fail(t.line, "Frame Time:", "Frame " + std::string(t.text));
  Token ft = lex.next();
  double frame_time = 0;
  if (!Lexer::parse_double(ft.text, frame_time) || !std::isfinite(frame_time) || frame_time <= 0)
    lex.fail(ft.line, "a positive Frame Time (s)", ft.text);
  bvh.frame_time = frame_time;
  Token extra;
  if (!lex.finish_line(extra)) lex.fail(extra.line, "end of line after Frame Time", extra.text);
  return frames;
}

// The MOTION lines from `p` (at line `line`): the hot loop. `frames` rows of
// channel_count values into bvh.values.
void read_motion_lines(const char* p, const char* const end, long line, long frames, const std::string& source,
                       Bvh& bvh) {
  const std::size_t cc = std::size_t(bvh.channel_count);
  // Each value takes at least two bytes ("0 "): never allocate past what the
  // remaining text could hold, whatever `Frames:` claims.
  const std::size_t most = std::size_t(end - p) / 2 + 1;
  bvh.values.resize(std::min(std::size_t(frames) * cc, (most / cc + 1) * cc));
  long read = 0;
  while (p < end) {
    while (p < end && is_space(*p)) ++p;
    if (p == end) break;
    if (*p == '\n') {  // blank line
      ++p;
      ++line;
      continue;
    }
    if (read == frames) throw Error::at(source, line, frame_lines(frames), "more");
    if ((std::size_t(read) + 1) * cc > bvh.values.size()) bvh.values.resize(bvh.values.size() * 2 + cc);
    double* out = bvh.values.data() + std::size_t(read) * cc;
    std::size_t count = 0;
    for (;;) {
      double v;
      bool ok;
      const char* stop = frame_value(p, end, v, ok);
      if (!ok || !std::isfinite(v)) {
        const char* e = p;
        while (e < end && !is_space(*e) && *e != '\n') ++e;
        std::string_view token(p, std::size_t(e - p));
        throw Error::at(source, line, ok ? "a finite number" : "a number", shown(token));
      }
      if (count < cc) out[count] = v;
      ++count;
      p = stop;
      while (p < end && is_space(*p)) ++p;
      if (p == end || *p == '\n') break;
    }
    if (count != cc) throw Error::at(source, line, std::to_string(cc) + " values", std::to_string(count));
    ++read;
    if (p < end) ++p;  // the '\n'
    ++line;
  }
  if (read != frames) throw Error::at(source, line, frame_lines(frames), std::to_string(read));
  bvh.values.resize(std::size_t(frames) * cc);
}

}  // namespace

Bvh parse_bvh(std::string_view text, const std::string& source) {
  Bvh bvh;
  bvh.source = source;
  Lexer lex(text, source);
  Token t = lex.next();
  if (t.text != "HIERARCHY") {
    if (!t.text.empty() && !is_bvh_keyword(t.text))
      throw Error::at(source, t.line, "HIERARCHY", "other text (not a BVH file)");
    lex.fail(t.line, "HIERARCHY", t.text);
  }
  t = lex.next();
  if (t.text != "ROOT") lex.fail(t.line, "ROOT", t.text);
  HierarchyParser(lex, bvh).joint(-1, t.line, 0);
  t = lex.next();
  if (t.text != "MOTION") lex.fail(t.line, "MOTION", t.text);
  if (bvh.channel_count == 0) lex.fail(t.line, "CHANNELS on at least one joint", "none");
  const long frames = parse_motion_header(lex, bvh);
  read_motion_lines(text.data() + lex.pos(), text.data() + text.size(), lex.line(), frames, source, bvh);
  return bvh;
}

Bvh read_bvh(const std::string& path) {
  note_input(path);
  std::string text = read_text_file(path);
  if (text.empty()) throw Error::at(path, 1, "HIERARCHY", "an empty file");
  return parse_bvh(text, path);
}

}  // namespace ptnet
