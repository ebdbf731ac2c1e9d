// The physics bench's outputs: results.json (every figure), index.html (a
// table and the force curves of each trial: plates, simulator, naive) and
// each trial's simulated forces as an OpenSim storage file.
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "plates_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/plates.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/viz.hpp"

namespace ptnet {
namespace {

// NaN as JSON null.
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::ordered_json source_json(const ForceSource& s) {
  nlohmann::ordered_json j;
  j["rmse_bw"] = number(s.rmse_bw);
  j["peak_error_pct"] = number(s.peak_error_pct);
  j["stance_error_ms"] = number(s.stance_error_ms);
  j["loading_rate_error_pct"] = number(s.loading_rate_error_pct);
  j["stride_impulse_error_pct"] = number(s.stride_impulse_error_pct);
  j["flight_recall"] = number(s.flight_recall);
  j["cop_rms_foot_lengths"] = number(s.cop_rms);
  j["contacts_matched"] = s.matched;
  nlohmann::json contacts = nlohmann::json::array();
  for (const Contact& c : s.contacts)
    contacts.push_back({{"foot", c.foot == 0 ? "left" : "right"},
                        {"start_s", c.start_s},
                        {"stance_ms", 1000 * (c.end_s - c.start_s)},
                        {"peak_n", c.peak_n},
                        {"impulse_ns", c.impulse_ns},
                        {"loading_rate_n_s", number(c.loading_rate_n_s)},
                        {"whole", c.whole}});
  j["contacts"] = contacts;
  return j;
}

// Every frame of a trial: time, then total, left, right force (BW) and the
// left and right CoP along the foot of the plates, the simulator and the
// naive reference.
void write_series(const GaitTrialResult& r, const std::string& path, bool force) {
  std::vector<std::string> columns{"time_s"};
  for (const ForceSource* s : {&r.plates, &r.simulated, &r.naive})
    for (const char* c : {"_total_bw", "_left_bw", "_right_bw", "_left_cop_u", "_right_cop_u"})
      columns.push_back(s->name + c);
  std::vector<std::vector<double>> rows;
  for (std::size_t t = 0; t < r.time_s.size(); ++t) {
    rows.push_back({r.time_s[t]});
    for (const ForceSource* s : {&r.plates, &r.simulated, &r.naive})
      rows.back().insert(rows.back().end(),
                         {s->total_bw[t], s->foot_bw[t][0], s->foot_bw[t][1], s->cop_u[t][0], s->cop_u[t][1]});
  }
  write_table_file(path, columns, rows, "", force);
}

std::string cell(double v, int digits) { return std::isfinite(v) ? fixed_text(v, digits) : "&ndash;"; }

// The three figures of a trial: the total force, the force per foot, and
// the centre of pressure along each loaded foot (0 heel, 1 toe tip).
enum class Chart { total, feet, cop };

std::string chart(const GaitTrialResult& r, Chart kind) {
  LineChart c;
  c.title = r.trial.name + (kind == Chart::total  ? ": total vertical force"
                            : kind == Chart::feet ? ": vertical force per foot"
                                                  : ": centre of pressure along the foot");
  c.x_label = "time (s)";
  c.y_label = kind == Chart::cop ? "CoP along the foot (0 heel, 1 toe)" : "force (body weights)";
  c.width = 900;
  c.points = false;
  for (const ForceSource* s : {&r.plates, &r.simulated, &r.naive}) {
    if (kind == Chart::total) {
      c.series.push_back({s->name, r.time_s, s->total_bw});
      continue;
    }
    if (s == &r.naive) continue;
    for (int f = 0; f < 2; ++f) {
      LineSeries l{s->name + (f == 0 ? " left" : " right"), r.time_s, {}};
      for (std::size_t t = 0; t < r.time_s.size(); ++t)
        l.y.push_back(kind == Chart::feet ? s->foot_bw[t][std::size_t(f)] : s->cop_u[t][std::size_t(f)]);
      c.series.push_back(std::move(l));
    }
  }
  return svg_line_chart(c);
}

std::vector<GaitTrial> trials_of(const std::vector<GaitTrialResult>& results) {
  std::vector<GaitTrial> out;
  for (const auto& r : results) out.push_back(r.trial);
  return out;
}

// A trial's entry of results.json.
nlohmann::ordered_json trial_json(const GaitTrialResult& r) {
  nlohmann::ordered_json j;
  j["trial"] = r.trial.name;
  j["body"] = {{"sex", sex_name(r.trial.body.sex)},
               {"height_cm", r.trial.body.height_cm},
               {"weight_kg", r.trial.body.weight_kg}};
  j["fps"] = r.fps;
  j["frames"] = r.time_s.size();
  j["treadmill_belt_mps"] = r.belt_mps;
  j["coverage"] = plate_coverage_name(r.coverage);
  j["compared_frames"] = std::count(r.compared.begin(), r.compared.end(), true);
  j["carried_frames"] = r.carried_frames;
  j["plate_flight_frames"] = r.flight_frames;
  j["single_stance_frames"] = r.single_stance_frames;
  j["plates"] = {{"contacts", source_json(r.plates)["contacts"]}};
  j["simulated"] = source_json(r.simulated);
  j["naive"] = source_json(r.naive);
  return j;
}

const char* const kPageHead =
    "<h1>ptnet physics bench: the simulator against force plates</h1>\n"
    "<p>Each trial's motion (markers) simulated on a body of the subject's sex, stature and mass, its "
    "vertical ground reaction force beside the trial's force plates on the same clock, and beside the "
    "naive reference (body weight shared by the feet the simulator puts in contact). BW: body weight. "
    "Every number: <a href=\"results.json\">results.json</a>; the simulated forces: "
    "<code>TRIAL_sim.mot</code> (OpenSim storage); every frame of the three: <code>TRIAL_frames.csv</code>.</p>\n"
    "<table id=\"physics\"><tr><th>trial</th><th>source</th><th>force RMSE (BW)</th><th>peak error (%)</th>"
    "<th>stance error (ms)</th><th>loading rate error (%)</th><th>stride impulse error (%)</th>"
    "<th>flight frames found</th><th>CoP along the foot, RMS (foot lengths)</th><th>whole contacts matched</th></tr>\n";

// A trial's rows of the page's table: the simulator and the naive reference.
void table_rows(std::ostream& b, const GaitTrialResult& r) {
  const long whole = std::count_if(r.plates.contacts.begin(), r.plates.contacts.end(), [](const Contact& c) { return c.whole; });
  for (const ForceSource* s : {&r.simulated, &r.naive}) {
    const std::string flight = std::isfinite(s->flight_recall)
                                   ? fixed_text(100 * s->flight_recall, 0) + " % of " + std::to_string(r.flight_frames)
                                   : "no flight";
    b << "<tr><td>" << html_escape(r.trial.name) << "</td><td>" << s->name << "</td><td class=\"num\">"
      << cell(s->rmse_bw, 3) << "</td><td class=\"num\">" << cell(s->peak_error_pct, 1) << "</td><td class=\"num\">"
      << cell(s->stance_error_ms, 0) << "</td><td class=\"num\">" << cell(s->loading_rate_error_pct, 0)
      << "</td><td class=\"num\">" << cell(s->stride_impulse_error_pct, 1) << "</td><td class=\"num\">" << flight
      << "</td><td class=\"num\">" << cell(s->cop_rms, 3) << "</td><td class=\"num\">" << s->matched << " of "
      << whole << "</td></tr>\n";
  }
}

// A trial's section of the page: the subject, what was compared, its charts.
void trial_section(std::ostream& b, const GaitTrialResult& r) {
  b << "<h2>" << html_escape(r.trial.name) << "</h2>\n<p>" << html_escape(sex_name(r.trial.body.sex)) << ", "
    << fixed_text(r.trial.body.height_cm, 1) << " cm, " << fixed_text(r.trial.body.weight_kg, 1) << " kg; "
    << fixed_text(r.fps, 0) << " frames/s; plates see " << (r.coverage == PlateCoverage::all ? "every step" : "some steps")
    << ": " << std::count(r.compared.begin(), r.compared.end(), true) << " of " << r.time_s.size() << " frames compared"
    << (r.carried_frames > 0 ? " (" + std::to_string(r.carried_frames) + " carried by a seat left out)" : std::string())
    << (r.belt_mps > 0 ? "; treadmill belt " + fixed_text(r.belt_mps, 2) + " m/s removed" : std::string()) << ".</p>\n"
    << "<img src=\"" << html_escape(r.trial.name) << "_total.svg\" alt=\"total vertical force\">\n"
    << "<img src=\"" << html_escape(r.trial.name) << "_feet.svg\" alt=\"vertical force per foot\">\n"
    << "<img src=\"" << html_escape(r.trial.name) << "_cop.svg\" alt=\"centre of pressure along the foot\">\n";
}

}  // namespace

void check_physics_report(const std::vector<GaitTrial>& trials, const std::string& out_dir, bool force) {
  std::vector<std::string> files = {"results.json", "index.html"};
  for (const GaitTrial& t : trials) {
    if (const std::string problem = name_problem(t.name); !problem.empty())
      throw Error::in(out_dir, "trial name " + escaped(t.name) + " " + problem + ": it names the trial's files");
    for (const char* suffix : {"_sim.mot", "_frames.csv", "_total.svg", "_feet.svg", "_cop.svg"})
      files.push_back(t.name + suffix);
  }
  if (const std::string twice = first_repeat(files); !twice.empty())
    throw Error::in(out_dir, "two trials would write " + escaped(twice) + ": every trial needs a name of its own");
  check_outputs_in_folder(out_dir, files, force);
}

void write_physics_report(const std::vector<GaitTrialResult>& results, const std::string& out_dir, bool force) {
  namespace fs = std::filesystem;
  check_physics_report(trials_of(results), out_dir, force);
  make_folder(out_dir);
  CommitGroup report;  // every file appears at the end, or none
  const auto path = [&](const std::string& name) { return (fs::path(out_dir) / name).string(); };
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  std::ostringstream b;
  b << kPageHead;
  for (const auto& r : results) {
    write_force_table(r.table, path(r.trial.name + "_sim.mot"), force);
    write_series(r, path(r.trial.name + "_frames.csv"), force);
    write_text_file(path(r.trial.name + "_total.svg"), chart(r, Chart::total), force);
    write_text_file(path(r.trial.name + "_feet.svg"), chart(r, Chart::feet), force);
    write_text_file(path(r.trial.name + "_cop.svg"), chart(r, Chart::cop), force);
    all.push_back(trial_json(r));
    table_rows(b, r);
  }
  b << "</table>\n";
  for (const auto& r : results) trial_section(b, r);
  write_text_file(path("results.json"), all.dump(2) + "\n", force);
  write_text_file(path("index.html"), html_page("ptnet physics bench", b.str()), force);
  report.commit();
}

}  // namespace ptnet
