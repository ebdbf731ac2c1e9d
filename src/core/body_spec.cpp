// Body attributes: parsing, validation, the bodies CSV and the paper's body
// distribution (ptnet/body_spec.hpp).
#include "ptnet/body_spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "core/body_spec_internal.hpp"
#include "core/csv.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

const std::string kHeightRange = number_text(kMinHeightCm) + "-" + number_text(kMaxHeightCm);
const std::string kWeightRange = number_text(kMinWeightKg) + "-" + number_text(kMaxWeightKg);

bool in_range(double v, double lo, double hi) { return v >= lo && v <= hi; }  // false for NaN

bool valid_role(const std::string& role) { return role == "retargeted" || role == "original"; }

double round1(double v) { return std::round(v * 10) / 10; }

}  // namespace

Sex parse_sex(const std::string& text) {
  const std::string s = lower(trim(text));
  if (s == "female" || s == "f" || s == "0") return Sex::female;
  if (s == "male" || s == "m" || s == "1") return Sex::male;
  throw Error("sex " + escaped(text) + " is not female or male");
}

const char* sex_name(Sex sex) { return sex == Sex::male ? "male" : "female"; }

std::string body_range_problem(const BodySpec& b) {
  if (!in_range(b.height_cm, kMinHeightCm, kMaxHeightCm))
    return "height_cm " + number_text(b.height_cm) + " outside " + kHeightRange;
  if (!in_range(b.weight_kg, kMinWeightKg, kMaxWeightKg))
    return "weight_kg " + number_text(b.weight_kg) + " outside " + kWeightRange;
  if (b.sex != Sex::female && b.sex != Sex::male) return "sex must be female or male";
  return "";
}

void check_body_range(const BodySpec& body, const std::string& what) {
  const std::string p = body_range_problem(body);
  if (!p.empty()) throw Error(what + ": " + p);
}

void validate(const BodySpec& body) {
  const std::string what = "body " + (body.id.empty() ? std::string("?") : body.id);
  check_body_range(body, what);
  if (!valid_role(body.role)) throw Error(what + ": role " + escaped(body.role) + " is not retargeted or original");
}

BodySpec parse_body_attributes(const std::string& text, const std::string& what) {
  const auto f = split(text, ',');
  BodySpec b;
  b.id = what;
  bool ok = f.size() == 3 && parse_number(f[1], b.height_cm) && parse_number(f[2], b.weight_kg);
  try {
    if (ok) b.sex = parse_sex(f[0]);
  } catch (const Error&) {
    ok = false;
  }
  if (!ok) throw Error(what + ": expected SEX,HEIGHT_CM,WEIGHT_KG like female,165,60, found " + escaped(text));
  return b;
}

BodySpec parse_body_fields(const std::string& file, long line, const std::string& id, const std::string& sex,
                           const std::string& height_cm, const std::string& weight_kg) {
  BodySpec b;
  b.id = id;
  if (b.id.empty()) throw Error::at(file, line, "a body id", "an empty id");
  try {
    b.sex = parse_sex(sex);
  } catch (const Error&) {
    throw Error::at(file, line, "sex female or male", escaped(sex));
  }
  if (!parse_number(height_cm, b.height_cm)) throw Error::at(file, line, "height_cm as a number", escaped(height_cm));
  if (!parse_number(weight_kg, b.weight_kg)) throw Error::at(file, line, "weight_kg as a number", escaped(weight_kg));
  if (!in_range(b.height_cm, kMinHeightCm, kMaxHeightCm))
    throw Error::at(file, line, "height_cm in " + kHeightRange, number_text(b.height_cm));
  if (!in_range(b.weight_kg, kMinWeightKg, kMaxWeightKg))
    throw Error::at(file, line, "weight_kg in " + kWeightRange, number_text(b.weight_kg));
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
    auto f = [&](int c) -> const std::string& { return CsvTable::field(row, c); };
    BodySpec b = parse_body_fields(path, row.line, f(c_id), f(c_sex), f(c_height), f(c_weight));
    if (c_role >= 0) {
      b.role = lower(f(c_role));
      if (b.role.empty()) b.role = "retargeted";
      if (!valid_role(b.role)) throw Error::at(path, row.line, "role retargeted or original", escaped(f(c_role)));
    }
    if (!ids.insert(b.id).second) throw Error::at(path, row.line, "a unique id", "duplicate id " + escaped(b.id));
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

double standard_normal(std::mt19937_64& rng) {
  auto uniform = [&] { return (double(rng() >> 11) + 0.5) * (1.0 / 9007199254740992.0); };
  const double u1 = uniform(), u2 = uniform();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

std::vector<std::array<double, 2>> latin_hypercube(int count, std::mt19937_64& rng) {
  auto permutation = [&] {
    std::vector<int> p(std::size_t(std::max(0, count)), 0);
    for (int i = 0; i < count; ++i) p[std::size_t(i)] = i;
    for (int i = count - 1; i > 0; --i) std::swap(p[std::size_t(i)], p[std::size_t(rng() % std::uint64_t(i + 1))]);
    return p;
  };
  const std::vector<int> a = permutation(), b = permutation();
  std::vector<std::array<double, 2>> out;
  for (int i = 0; i < count; ++i)
    out.push_back({(a[std::size_t(i)] + 0.5) / count, (b[std::size_t(i)] + 0.5) / count});
  return out;
}

BodySpec paper_body_at(Sex sex, double height_sd, double weight_sd, const std::string& id, const std::string& role) {
  const BodyDistribution& d = sex == Sex::male ? kPaperMale : kPaperFemale;
  BodySpec b;
  b.id = id;
  b.sex = sex;
  b.height_cm = round1(std::clamp(d.height_mean_cm + d.height_sd_cm * height_sd, kMinHeightCm, kMaxHeightCm));
  b.weight_kg = round1(std::clamp(d.weight_mean_kg + d.weight_sd_kg * weight_sd, kMinWeightKg, kMaxWeightKg));
  b.role = role;
  return b;
}

BodySpec draw_paper_body(std::mt19937_64& rng, Sex sex, const std::string& id, const std::string& role) {
  const double height_sd = standard_normal(rng);  // height first: the same bodies as ever
  const double weight_sd = standard_normal(rng);
  return paper_body_at(sex, height_sd, weight_sd, id, role);
}

}  // namespace ptnet
