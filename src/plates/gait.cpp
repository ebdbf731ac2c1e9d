// Gait events and figures of a vertical-force series: contacts (threshold
// crossings interpolated between samples), peaks, impulses, loading rates;
// and the comparison of a source with the plates (plates_internal.hpp).
#include <algorithm>
#include <cmath>

#include "plates_internal.hpp"

namespace ptnet {

std::vector<Contact> find_contacts(const std::vector<double>& t, const std::vector<double>& f, double threshold,
                                   int foot) {
  std::vector<Contact> out;
  const std::size_t n = std::min(t.size(), f.size());
  // Where the force crosses the threshold between samples i - 1 and i.
  auto crossing = [&](std::size_t i) {
    const double a = f[i - 1] - threshold, b = f[i] - threshold;
    return a == b ? t[i] : t[i - 1] + (t[i] - t[i - 1]) * a / (a - b);
  };
  for (std::size_t i = 0; i < n;) {
    if (!(f[i] > threshold)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && f[j] > threshold) ++j;  // contact samples [i, j)
    Contact c;
    c.foot = foot;
    c.start_s = i > 0 ? crossing(i) : t[i];
    c.end_s = j < n ? crossing(j) : t[j - 1];
    c.whole = i > 0 && j < n;
    std::size_t at_peak = i;
    for (std::size_t k = i; k < j; ++k) {
      if (f[k] > c.peak_n) c.peak_n = f[k], at_peak = k;
      if (k + 1 < n) c.impulse_ns += 0.5 * (f[k] + f[k + 1]) * (t[k + 1] - t[k]);
    }
    if (i > 0) c.impulse_ns += 0.5 * (f[i - 1] + f[i]) * (t[i] - t[i - 1]);
    // Rising edge: the first times the force passes 20 % and 80 % of the peak.
    auto rise = [&](double level) -> double {
      for (std::size_t k = std::max<std::size_t>(i, 1); k <= at_peak; ++k)
        if (f[k] >= level && f[k - 1] < level) return t[k - 1] + (t[k] - t[k - 1]) * (level - f[k - 1]) / (f[k] - f[k - 1]);
      return NAN;
    };
    const double t20 = rise(0.2 * c.peak_n), t80 = rise(0.8 * c.peak_n);
    c.loading_rate_n_s = t80 > t20 ? 0.6 * c.peak_n / (t80 - t20) : NAN;
    out.push_back(c);
    i = j;
  }
  return out;
}

namespace detail {

std::vector<double> resample_box(const std::vector<double>& t, const std::vector<double>& v,
                                 const std::vector<double>& at, double dt) {
  std::vector<double> out(at.size(), NAN);
  std::size_t k = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double lo = at[i] - 0.5 * dt, hi = at[i] + 0.5 * dt;
    while (k < t.size() && t[k] < lo) ++k;
    double sum = 0;
    int n = 0;
    for (std::size_t j = k; j < t.size() && t[j] < hi; ++j) sum += v[j], ++n;
    if (n > 0) {
      out[i] = sum / n;
    } else if (k > 0 && k < t.size()) {  // samples sparser than the frames: linear
      const double a = (at[i] - t[k - 1]) / (t[k] - t[k - 1]);
      out[i] = (1 - a) * v[k - 1] + a * v[k];
    }
  }
  return out;
}

namespace {

double mean(const std::vector<double>& v) {
  double s = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) s += x, ++n;
  return n ? s / n : NAN;
}

double overlap(const Contact& a, const Contact& b) {
  return std::min(a.end_s, b.end_s) - std::max(a.start_s, b.start_s);
}

// RMS difference of the total force over the compared frames both have.
double force_rmse(const ForceSource& s, const ForceSource& plates, const Frames& f) {
  double se = 0;
  int n = 0;
  for (std::size_t t = 0; t < f.time_s.size(); ++t) {
    if (!f.compared[t] || !std::isfinite(plates.total_bw[t]) || !std::isfinite(s.total_bw[t])) continue;
    const double d = s.total_bw[t] - plates.total_bw[t];
    se += d * d, ++n;
  }
  return n ? std::sqrt(se / n) : NAN;
}

// The fraction of the plates' flight frames (compared, both known) in
// flight here too.
double flight_recall(const ForceSource& s, const ForceSource& plates, const Frames& f, const CompareOptions& o) {
  int flight = 0, hit = 0;
  for (std::size_t t = 0; t < f.time_s.size(); ++t) {
    if (!f.compared[t] || !std::isfinite(plates.total_bw[t]) || !std::isfinite(s.total_bw[t])) continue;
    if (plates.total_bw[t] < o.flight_bw) {
      ++flight;
      hit += s.total_bw[t] < o.flight_bw;
    }
  }
  return flight ? double(hit) / flight : NAN;
}

// The plates' stances (whole, at least stance_bw at their peak, every
// frame compared), each with the contact of s of the same foot that
// overlaps it most; stances s misses are left out.
std::vector<std::pair<const Contact*, const Contact*>> matched_stances(const ForceSource& s, const ForceSource& plates,
                                                                      const Frames& f, const CompareOptions& o) {
  const auto all_compared = [&](const Contact& c) {
    for (std::size_t t = 0; t < f.time_s.size(); ++t)
      if (f.time_s[t] >= c.start_s && f.time_s[t] <= c.end_s && !f.compared[t]) return false;
    return true;
  };
  std::vector<std::pair<const Contact*, const Contact*>> out;  // plates', s's
  for (const Contact& p : plates.contacts) {
    if (!p.whole || p.peak_n < o.stance_bw * o.weight_n || !all_compared(p)) continue;
    const Contact* best = nullptr;
    for (const Contact& c : s.contacts)
      if (c.foot == p.foot && overlap(c, p) > 0 && (!best || overlap(c, p) > overlap(*best, p))) best = &c;
    if (best) out.emplace_back(&p, best);
  }
  return out;
}

// Mean over the matched stances of `error(plates', s's)`; NaN errors left out.
template <typename F>
double mean_error(const std::vector<std::pair<const Contact*, const Contact*>>& pairs, F error) {
  std::vector<double> v;
  for (const auto& [p, c] : pairs) v.push_back(error(*p, *c));
  return mean(v);
}

// Strides: from one contact of a foot to its next (the plates' events); the
// mean error of the total force's impulse over each, every frame compared.
double stride_impulse_error_pct(const ForceSource& s, const ForceSource& plates, const Frames& f) {
  std::vector<double> stride;
  for (std::size_t a = 0; a < plates.contacts.size(); ++a)
    for (std::size_t b = a + 1; b < plates.contacts.size(); ++b) {
      if (plates.contacts[b].foot != plates.contacts[a].foot || !plates.contacts[a].whole) continue;
      const double t0 = plates.contacts[a].start_s, t1 = plates.contacts[b].start_s;
      double ip = 0, is = 0;
      bool ok = true;
      for (std::size_t t = 0; t + 1 < f.time_s.size(); ++t) {
        if (f.time_s[t] < t0 || f.time_s[t + 1] > t1) continue;
        const double dt = f.time_s[t + 1] - f.time_s[t];
        const double pp = plates.total_bw[t] + plates.total_bw[t + 1], ss = s.total_bw[t] + s.total_bw[t + 1];
        ok = ok && std::isfinite(pp) && std::isfinite(ss) && f.compared[t] && f.compared[t + 1];
        ip += 0.5 * pp * dt, is += 0.5 * ss * dt;
      }
      if (ok && ip > 0) stride.push_back(100 * std::abs(is - ip) / ip);
      break;
    }
  return mean(stride);
}

// Centre of pressure along the foot, in single stance (the plates load one
// foot): the RMS difference (foot lengths).
double cop_rms(const ForceSource& s, const ForceSource& plates, const Frames& f, const CompareOptions& o) {
  double ce = 0;
  int cn = 0;
  for (std::size_t t = 0; t < f.time_s.size(); ++t) {
    if (!f.compared[t]) continue;
    const auto& pf = plates.foot_bw[t];
    const bool left = pf[0] > o.contact_bw, right = pf[1] > o.contact_bw;
    if (left == right) continue;
    const int foot = left ? 0 : 1;
    const double pu = plates.cop_u[t][std::size_t(foot)], su = s.cop_u[t][std::size_t(foot)];
    if (!std::isfinite(pu) || !std::isfinite(su)) continue;
    ce += (su - pu) * (su - pu), ++cn;
  }
  return cn ? std::sqrt(ce / cn) : NAN;
}

}  // namespace

void compare_with_plates(ForceSource& s, const ForceSource& plates, const Frames& f, const CompareOptions& o) {
  s.rmse_bw = force_rmse(s, plates, f);
  s.flight_recall = flight_recall(s, plates, f, o);
  const auto stances = matched_stances(s, plates, f, o);
  s.matched = int(stances.size());
  s.peak_error_pct = mean_error(stances, [](const Contact& p, const Contact& c) {
    return 100 * std::abs(c.peak_n - p.peak_n) / p.peak_n;
  });
  s.stance_error_ms = mean_error(stances, [](const Contact& p, const Contact& c) {
    return 1000 * std::abs((c.end_s - c.start_s) - (p.end_s - p.start_s));
  });
  s.loading_rate_error_pct = mean_error(stances, [](const Contact& p, const Contact& c) {
    return std::isfinite(p.loading_rate_n_s) && std::isfinite(c.loading_rate_n_s)
               ? 100 * std::abs(c.loading_rate_n_s - p.loading_rate_n_s) / p.loading_rate_n_s
               : NAN;
  });
  s.stride_impulse_error_pct = stride_impulse_error_pct(s, plates, f);
  s.cop_rms = cop_rms(s, plates, f, o);
}

}  // namespace detail
}  // namespace ptnet
