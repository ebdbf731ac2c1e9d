// Body attributes: parsing, validation and the bodies CSV.
#include "ptnet/body_spec.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <set>
#include <sstream>

#include "ptnet/csv.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
namespace {

std::string trim(const std::string& s) {
  std::size_t b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::string lower(std::string s) {
  for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == sep) {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(trim(cur));
  return out;
}

// Parses a finite number; false if `text` is not entirely one.
bool parse_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

std::string quote(const std::string& s) { return escaped(s); }

// The problem with a body's values, or "" if it is valid.
std::string problem(const BodySpec& b) {
  if (!std::isfinite(b.height_cm) || b.height_cm < kMinHeightCm || b.height_cm > kMaxHeightCm)
    return "height_cm " + number_text(b.height_cm) + " outside 100-230";
  if (!std::isfinite(b.weight_kg) || b.weight_kg < kMinWeightKg || b.weight_kg > kMaxWeightKg)
    return "weight_kg " + number_text(b.weight_kg) + " outside 20-250";
  if (b.sex != Sex::female && b.sex != Sex::male) return "sex must be female or male";
  if (b.role != "retargeted" && b.role != "original")
    return "role " + quote(b.role) + " is not retargeted or original";
  return "";
}

}  // namespace

Sex parse_sex(const std::string& text) {
  std::string s = lower(trim(text));
  if (s == "female" || s == "f" || s == "0") return Sex::female;
  if (s == "male" || s == "m" || s == "1") return Sex::male;
  throw Error("sex " + quote(text) + " is not female or male");
}

const char* sex_name(Sex sex) { return sex == Sex::male ? "male" : "female"; }

void validate(const BodySpec& body) {
  std::string p = problem(body);
  if (!p.empty()) throw Error("body " + (body.id.empty() ? std::string("?") : body.id) + ": " + p);
}

BodySpec parse_body_attributes(const std::string& text) {
  auto f = split(text, ',');
  if (f.size() != 3)
    throw Error("body attributes " + quote(text) + ": expected SEX,HEIGHT_CM,WEIGHT_KG (e.g. female,165,60)");
  BodySpec b;
  b.id = "body";
  b.sex = parse_sex(f[0]);
  if (!parse_number(f[1], b.height_cm))
    throw Error("body attributes " + quote(text) + ": height_cm " + quote(f[1]) + " is not a number");
  if (!parse_number(f[2], b.weight_kg))
    throw Error("body attributes " + quote(text) + ": weight_kg " + quote(f[2]) + " is not a number");
  std::string p = problem(b);
  if (!p.empty()) throw Error("body attributes " + quote(text) + ": " + p);
  return b;
}

std::vector<BodySpec> read_bodies_csv(const std::string& path) {
  note_input(path);
  return parse_bodies_csv(read_text_file(path), path);
}

std::vector<BodySpec> parse_bodies_csv(const std::string& text, const std::string& path) {
  const CsvTable t = parse_csv(text, path);
  const std::string columns = "id,sex,height_cm,weight_kg[,role]";
  const int c_id = t.required("id", columns), c_sex = t.required("sex", columns),
            c_height = t.required("height_cm", columns), c_weight = t.required("weight_kg", columns),
            c_role = t.column("role");
  std::vector<BodySpec> bodies;
  std::set<std::string> ids;
  for (const CsvRow& row : t.rows) {
    const long number = row.line;
    auto f = [&](int c) -> const std::string& { return CsvTable::field(row, c); };
    BodySpec b;
    b.id = f(c_id);
    if (b.id.empty()) throw Error::at(path, number, "a body id", "an empty id");
    try {
      b.sex = parse_sex(f(c_sex));
    } catch (const Error&) {
      throw Error::at(path, number, "sex female or male", escaped(f(c_sex)));
    }
    if (!parse_number(f(c_height), b.height_cm))
      throw Error::at(path, number, "height_cm as a number", escaped(f(c_height)));
    if (!parse_number(f(c_weight), b.weight_kg))
      throw Error::at(path, number, "weight_kg as a number", escaped(f(c_weight)));
    if (b.height_cm < kMinHeightCm || b.height_cm > kMaxHeightCm)
      throw Error::at(path, number, "height_cm in 100-230", number_text(b.height_cm));
    if (b.weight_kg < kMinWeightKg || b.weight_kg > kMaxWeightKg)
      throw Error::at(path, number, "weight_kg in 20-250", number_text(b.weight_kg));
    if (c_role >= 0) {
      b.role = lower(f(c_role));
      if (b.role.empty()) b.role = "retargeted";
      if (b.role != "retargeted" && b.role != "original")
        throw Error::at(path, number, "role retargeted or original", escaped(f(c_role)));
    }
    if (!ids.insert(b.id).second) throw Error::at(path, number, "a unique id", "duplicate id " + escaped(b.id));
    bodies.push_back(b);
  }
  if (bodies.empty()) throw Error::in(path, "no bodies after the header");
  return bodies;
}

std::string format_bodies_csv(const std::vector<BodySpec>& bodies) {
  std::string out = "id,sex,height_cm,weight_kg,role\n";
  for (const auto& b : bodies) {
    validate(b);
    char buf[64];
    std::snprintf(buf, sizeof buf, ",%.10g,%.10g,", b.height_cm, b.weight_kg);
    out += csv_field(b.id) + "," + sex_name(b.sex) + buf + b.role + "\n";
  }
  return out;
}

}  // namespace ptnet
