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

}  // namespace

void compare_with_plates(ForceSource& s, const ForceSource& plates, const std::vector<double>& time_s,
                         const std::vector<bool>& compared, const CompareOptions& o) {
  // Total force over the frames both have.
  double se = 0;
  int n = 0, flight = 0, flight_hit = 0;
  for (std::size_t t = 0; t < time_s.size(); ++t) {
    if (!compared[t] || !std::isfinite(plates.total_bw[t]) || !std::isfinite(s.total_bw[t])) continue;
    const double d = s.total_bw[t] - plates.total_bw[t];
    se += d * d, ++n;
    if (plates.total_bw[t] < o.flight_bw) {
      ++flight;
      flight_hit += s.total_bw[t] < o.flight_bw;
    }
  }
  s.rmse_bw = n ? std::sqrt(se / n) : NAN;
  s.flight_recall = flight ? double(flight_hit) / flight : NAN;
  // Contacts matched to the plates' by the largest overlap, foot by foot.
  std::vector<double> peak, stance, rate;
  s.matched = 0;
  const auto all_compared = [&](const Contact& c) {
    for (std::size_t t = 0; t < time_s.size(); ++t)
      if (time_s[t] >= c.start_s && time_s[t] <= c.end_s && !compared[t]) return false;
    return true;
  };
  for (const Contact& p : plates.contacts) {
    if (!p.whole || p.peak_n < o.stance_bw * o.weight_n || !all_compared(p)) continue;
    const Contact* best = nullptr;
    for (const Contact& c : s.contacts)
      if (c.foot == p.foot && overlap(c, p) > 0 && (!best || overlap(c, p) > overlap(*best, p))) best = &c;
    if (!best) continue;
    ++s.matched;
    peak.push_back(100 * std::abs(best->peak_n - p.peak_n) / p.peak_n);
    stance.push_back(1000 * std::abs((best->end_s - best->start_s) - (p.end_s - p.start_s)));
    if (std::isfinite(p.loading_rate_n_s) && std::isfinite(best->loading_rate_n_s))
      rate.push_back(100 * std::abs(best->loading_rate_n_s - p.loading_rate_n_s) / p.loading_rate_n_s);
  }
  s.peak_error_pct = mean(peak);
  s.stance_error_ms = mean(stance);
  s.loading_rate_error_pct = mean(rate);
  // Strides: from one contact of a foot to its next (the plates' events);
  // the impulse of the total force over each.
  std::vector<double> stride;
  for (std::size_t a = 0; a < plates.contacts.size(); ++a)
    for (std::size_t b = a + 1; b < plates.contacts.size(); ++b) {
      if (plates.contacts[b].foot != plates.contacts[a].foot || !plates.contacts[a].whole) continue;
      const double t0 = plates.contacts[a].start_s, t1 = plates.contacts[b].start_s;
      double ip = 0, is = 0;
      bool ok = true;
      for (std::size_t t = 0; t + 1 < time_s.size(); ++t) {
        if (time_s[t] < t0 || time_s[t + 1] > t1) continue;
        const double dt = time_s[t + 1] - time_s[t];
        const double pp = plates.total_bw[t] + plates.total_bw[t + 1], ss = s.total_bw[t] + s.total_bw[t + 1];
        ok = ok && std::isfinite(pp) && std::isfinite(ss) && compared[t] && compared[t + 1];
        ip += 0.5 * pp * dt, is += 0.5 * ss * dt;
      }
      if (ok && ip > 0) stride.push_back(100 * std::abs(is - ip) / ip);
      break;
    }
  s.stride_impulse_error_pct = mean(stride);
  // Centre of pressure along the foot, in single stance (the plates load one foot).
  double ce = 0;
  int cn = 0;
  for (std::size_t t = 0; t < time_s.size(); ++t) {
    if (!compared[t]) continue;
    const auto& pf = plates.foot_bw[t];
    const bool left = pf[0] > o.contact_bw, right = pf[1] > o.contact_bw;
    if (left == right) continue;
    const int f = left ? 0 : 1;
    const double pu = plates.cop_u[t][std::size_t(f)], su = s.cop_u[t][std::size_t(f)];
    if (!std::isfinite(pu) || !std::isfinite(su)) continue;
    ce += (su - pu) * (su - pu), ++cn;
  }
  s.cop_rms = cn ? std::sqrt(ce / cn) : NAN;
}

}  // namespace detail
}  // namespace ptnet
