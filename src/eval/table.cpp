// Table 2 of the paper from evaluated rows; metrics.csv in and out (eval.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "core/csv.hpp"
#include "eval/eval_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

const std::vector<std::string> kCategoryOrder{"walking", "rom", "freestyle", "acting"};
const std::vector<std::string> kMethodOrder{"model", "model_raw", "copy", "weight_ratio", "body_scale", "floor"};

void accumulate(SequenceMetrics& sum, const SequenceMetrics& m) {
  sum.rmse_kpa += m.rmse_kpa;
  sum.binary_r2 += m.binary_r2;
  sum.cop_error_cm += m.cop_error_cm;
  sum.cop_frames += m.cop_frames;
  sum.force_error_pct += m.force_error_pct;
  sum.contact_iou += m.contact_iou;
}

SequenceMetrics divide(SequenceMetrics s, int n) {
  if (n == 0) return s;
  s.rmse_kpa /= n;
  s.binary_r2 /= n;
  s.cop_error_cm /= n;
  s.force_error_pct /= n;
  s.contact_iou /= n;
  return s;
}

std::vector<std::string> ordered(std::vector<std::string> found,
                                 const std::vector<std::string>& preferred) {
  std::sort(found.begin(), found.end(), [&](const std::string& a, const std::string& b) {
    auto ia = std::find(preferred.begin(), preferred.end(), a) - preferred.begin();
    auto ib = std::find(preferred.begin(), preferred.end(), b) - preferred.begin();
    return ia != ib ? ia < ib : a < b;
  });
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

}  // namespace

std::vector<GroupSummary> summarise(const std::vector<EvalRow>& rows) {
  std::vector<std::string> methods, categories;
  for (const auto& r : rows) {
    methods.push_back(r.method);
    categories.push_back(r.category);
  }
  methods = ordered(methods, kMethodOrder);
  categories = ordered(categories, kCategoryOrder);
  std::vector<GroupSummary> out;
  for (bool seen : {true, false})
    for (const auto& method : methods) {
      GroupSummary avg{method, "average", seen, 0, {}};
      for (const auto& category : categories) {
        GroupSummary g{method, category, seen, 0, {}};
        for (const auto& r : rows)
          if (r.method == method && r.category == category && (r.take == 1) == seen) {
            accumulate(g.mean, r.metrics);
            accumulate(avg.mean, r.metrics);
            ++g.rows;
            ++avg.rows;
          }
        if (g.rows == 0) continue;
        g.mean = divide(g.mean, g.rows);
        out.push_back(g);
      }
      if (avg.rows == 0) continue;
      avg.mean = divide(avg.mean, avg.rows);
      out.push_back(avg);
    }
  return out;
}

std::string format_table(const std::vector<EvalRow>& rows) {
  const auto groups = summarise(rows);
  std::vector<std::string> methods{"floor"};  // always: "n/a" when not measured
  for (const auto& g : groups) methods.push_back(g.method);
  methods = ordered(methods, kMethodOrder);
  const bool has_floor = std::any_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.method == "floor"; });
  auto find = [&](const std::string& method, const std::string& group, bool seen)
      -> const GroupSummary* {
    for (const auto& g : groups)
      if (g.method == method && g.group == group && g.seen == seen) return &g;
    return nullptr;
  };
  const bool has_model = std::find(methods.begin(), methods.end(), "model") != methods.end();
  std::ostringstream out;
  out << "| Motion category | pairs |";
  for (const auto& m : methods) out << " RMSE " << m << " (kPa) | bin. R^2 " << m << " |";
  if (has_model) out << " CoP err. model (cm) | force err. model (%) | IoU model |";
  out << "\n|---|---:|";
  for (std::size_t i = 0; i < methods.size(); ++i) out << "---:|---:|";
  if (has_model) out << "---:|---:|---:|";
  out << "\n";
  for (bool seen : {true, false}) {
    std::vector<std::string> cats;
    for (const auto& g : groups)
      if (g.seen == seen && g.group != "average") cats.push_back(g.group);
    cats = ordered(cats, kCategoryOrder);
    if (cats.empty()) continue;
    const int blank = 1 + 2 * int(methods.size()) + (has_model ? 3 : 0);
    out << "| **" << (seen ? "Seen motions (take 1)" : "Unseen motions (take 2)") << "** |";
    for (int i = 0; i < blank; ++i) out << " |";
    out << "\n";
    cats.push_back("average");
    for (const auto& cat : cats) {
      const GroupSummary* first = find(methods.front(), cat, seen);
      out << "| " << (cat == "average" ? "**Average**" : cat) << " | "
          << (first ? first->rows : 0) << " |";
      for (const auto& m : methods) {
        const GroupSummary* g = find(m, cat, seen);
        const char* none = m == "floor" && !has_floor ? "n/a" : "-";
        out << " " << (g ? fixed_text(g->mean.rmse_kpa, m == "floor" ? 3 : 2) : none) << " | "
            << (g ? fixed_text(g->mean.binary_r2, 3) : none) << " |";
      }
      if (has_model) {
        const GroupSummary* g = find("model", cat, seen);
        out << " " << (g ? fixed_text(g->mean.cop_error_cm, 2) : "-") << " | "
            << (g ? fixed_text(g->mean.force_error_pct, 1) : "-") << " | "
            << (g ? fixed_text(g->mean.contact_iou, 3) : "-") << " |";
      }
      out << "\n";
    }
  }
  if (!has_floor) out << "\n" << kNoFloorNote << "\n";
  return out.str();
}

namespace {
const std::vector<std::string> kCsvColumns{
    "method",      "motion_id",   "category",   "take",     "source_sequence", "target_sequence",
    "source_body", "target_body", "frames",     "rmse_kpa", "binary_r2",       "cop_error_cm",
    "cop_frames",  "force_error_pct", "contact_iou"};

std::string full(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
}  // namespace

// RFC 4180 (core's csv_text_field for the text columns: names come from
// user files, e.g. a BVH named "walk, fast.bvh" or a body id "=HYPERLINK(...)").
std::string format_metrics_csv(const std::vector<EvalRow>& rows) {
  std::ostringstream out;
  out << join(kCsvColumns) << "\n";
  for (const auto& r : rows) {
    const auto& m = r.metrics;
    out << csv_text_field(r.method) << ',' << csv_text_field(r.motion_id) << ',' << csv_text_field(r.category)
        << ',' << r.take << ',' << csv_text_field(r.source_sequence) << ',' << csv_text_field(r.target_sequence)
        << ',' << csv_text_field(r.source_body) << ',' << csv_text_field(r.target_body) << ',' << r.frames << ','
        << full(m.rmse_kpa) << ',' << full(m.binary_r2) << ',' << full(m.cop_error_cm) << ',' << m.cop_frames << ','
        << full(m.force_error_pct) << ',' << full(m.contact_iou) << "\n";
  }
  return out.str();
}

std::vector<EvalRow> parse_metrics_csv(const std::string& text, const std::string& source) {
  const CsvTable t = parse_csv(text, source);
  const std::string columns = join(kCsvColumns);
  std::map<std::string, int> index;  // column name -> field index
  for (const auto& name : kCsvColumns) index[name] = t.required(name, columns);
  std::vector<EvalRow> rows;
  for (const CsvRow& row : t.rows) {
    const auto field = [&](const std::string& name) -> const std::string& {
      return CsvTable::field(row, index.at(name));
    };
    const auto text_of = [&](const std::string& name) { return csv_text_value(field(name)); };
    const auto number = [&](const std::string& name) {  // as printed by full(): nan and inf too
      const std::string& f = field(name);
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      if (f.empty() || *end != '\0')
        throw Error::at(source, row.line, "a number in column " + name, escaped(f));
      return v;
    };
    const auto integer = [&](const std::string& name) {
      const double v = number(name);
      if (!(v == std::floor(v) && std::abs(v) < 2e9))
        throw Error::at(source, row.line, "a whole number in column " + name, escaped(field(name)));
      return int(v);
    };
    EvalRow r;
    r.method = text_of("method");
    r.motion_id = text_of("motion_id");
    r.category = text_of("category");
    r.take = integer("take");
    r.source_sequence = text_of("source_sequence");
    r.target_sequence = text_of("target_sequence");
    r.source_body = text_of("source_body");
    r.target_body = text_of("target_body");
    r.frames = integer("frames");
    r.metrics.rmse_kpa = number("rmse_kpa");
    r.metrics.binary_r2 = number("binary_r2");
    r.metrics.cop_error_cm = number("cop_error_cm");
    r.metrics.cop_frames = integer("cop_frames");
    r.metrics.force_error_pct = number("force_error_pct");
    r.metrics.contact_iou = number("contact_iou");
    rows.push_back(r);
  }
  return rows;
}

}  // namespace ptnet
