// The plantar sole surface: outline and soft-tissue height profile of a bare
// foot, in normalised coordinates (u along the foot from the heel back, v
// across in foot widths, medial positive).
//
// Regions (docs/anthropometry.md): heel pad u 0-0.3, midfoot 0.3-0.6
// (medial arch raised ~1-2 cm, lateral band in contact), metatarsal heads
// ~0.65-0.75, toes ~0.8-1.0; foot length 0.152 H, width 0.055 H (Drillis &
// Contini 1966). Heights are millimetres of unloaded soft tissue above the
// sole plane: the lowest points (heel centre, metatarsal heads) carry the most
// pressure once the compliance band is applied by the simulator.
#include "foot_sole.hpp"

#include <algorithm>
#include <cmath>

#include "core/anthropometry.hpp"

namespace ptnet::detail {
namespace {

double clamp01(double t) { return std::min(1.0, std::max(0.0, t)); }
double smoothstep(double a, double b, double x) {
  double t = clamp01((x - a) / (b - a));
  return t * t * (3 - 2 * t);
}
double lerp(double a, double b, double t) { return a + (b - a) * t; }
// Bell-shaped bump (cosine window) of half-width w around c, 1 at c.
double bell(double c, double w, double x) {
  double d = std::abs(x - c) / w;
  return d >= 1 ? 0 : 0.5 * (1 + std::cos(M_PI * d));
}

// Medial and lateral extent of the outline (foot widths from the foot axis,
// the line under the ankle and the toe joint) at u. The foot is not
// symmetric about that axis: the heel is narrow and centred, the forefoot
// widens mostly laterally (1st metatarsal head ~0.42 W medial, 5th ~0.58 W
// lateral of the 2nd ray), so two feet standing side by side keep a gap.
double medial_edge(double u) {
  if (u < 0.12) return 0.32 * std::sqrt(std::max(0.0, 1 - std::pow((0.12 - u) / 0.12, 2)));
  if (u < 0.30) return 0.32;
  if (u < 0.62) return lerp(0.32, 0.40, smoothstep(0.30, 0.62, u));
  if (u < 0.74) return lerp(0.40, 0.42, (u - 0.62) / 0.12);
  return lerp(0.42, 0.38, smoothstep(0.74, 1.0, u));
}
double lateral_edge(double u) {
  if (u < 0.12) return 0.32 * std::sqrt(std::max(0.0, 1 - std::pow((0.12 - u) / 0.12, 2)));
  if (u < 0.30) return lerp(0.32, 0.36, (u - 0.12) / 0.18);
  if (u < 0.66) return lerp(0.36, 0.56, smoothstep(0.30, 0.66, u));
  if (u < 0.76) return 0.58;
  return lerp(0.58, 0.50, smoothstep(0.76, 0.90, u));
}

// Forward end of the toes at v: the hallux (medial) reaches the tip, the
// little toe ends at ~0.84 of the foot length.
double toe_tip(double v) {
  if (v > 0.15) return 1.0;
  double t = (0.15 - v) / 0.65;
  return 1.0 - 0.16 * t * t;
}

}  // namespace

SoleSurface make_sole_surface(const BodySpec& spec) {
  namespace A = anthropometry;
  const double h = spec.height_cm / 100.0;
  const double bmi = spec.weight_kg / (h * h);
  const double heavy = bmi / 22.0;  // 1 for a typical adult (BMI 22)

  SoleSurface s;
  s.length_m = A::kDrillisContini.foot_length * h;
  // A heavier foot spreads: width grows with BMI (soft tissue), clamped.
  s.width_m = A::kDrillisContini.foot_width * h * std::clamp(std::pow(heavy, 0.3), 0.85, 1.3);
  s.ankle_height_m = A::kDrillisContini.ankle * h;
  s.ankle_u = A::kFoot.ankle;
  s.mtp_u = A::kFoot.mtp;
  // Medial arch ~1-2 cm for a 26 cm foot, flattened by load.
  s.arch_height_m = 0.015 * (s.length_m / 0.26) * std::clamp(std::pow(1.0 / heavy, 0.7), 0.4, 1.3);
  // Soft tissue bulges more under a heavier body: the profile flattens.
  const double soft = std::clamp(std::pow(1.0 / heavy, 0.5), 0.6, 1.3);

  s.nu = 101;
  s.nv = 61;
  s.height_m.assign(std::size_t(s.nu) * s.nv, SoleSurface::kOutside);
  const double arch_mm = s.arch_height_m * 1000;
  for (int i = 0; i < s.nu; ++i) {
    double u = double(i) / (s.nu - 1);
    for (int j = 0; j < s.nv; ++j) {
      double v = s.v_min + (s.v_max - s.v_min) * j / (s.nv - 1);
      bool inside = v <= medial_edge(u) && -v <= lateral_edge(u) && u <= toe_tip(v);
      if (!inside) continue;
      // Heel pad: a bowl, lowest under the calcaneal tuberosity.
      double r2 = std::pow((u - 0.14) / 0.17, 2) + std::pow(v / 0.33, 2);
      double heel = 15.0 * soft * r2;
      // Midfoot: the lateral band a few mm up, the medial arch raised.
      double mid = 7.0 * soft + arch_mm * bell(0.47, 0.30, u) * smoothstep(-0.30, 0.25, v);
      // Metatarsal heads: a transverse ridge, lowest under the 2nd-3rd heads.
      double mth = soft * (1.0 + 7.0 * std::pow((u - 0.70) / 0.09, 2) + 16.0 * std::pow(v - 0.05, 2));
      // Toes: the hallux (medial) lower than the lesser toes; the sulcus
      // between the heads and the toe pads is raised.
      // Five toe pads: the hallux medial (v > 0.12), four lesser toes
      // across the rest, each a bowl separated by shallow gaps.
      double toes;
      if (v > 0.12) {
        toes = soft * (2.5 + 10.0 * std::pow((v - 0.27) / 0.16, 2) + 8.0 * std::pow((u - 0.90) / 0.08, 2));
      } else {
        double pad = (v + 0.52) / 0.64 * 4;  // 0..4 across the lesser toes
        double within = pad - std::floor(pad) - 0.5;
        double tip = 0.84 + 0.04 * std::min(pad, 4.0) / 4;  // pad centre along u
        toes = soft * (4.5 + 12.0 * within * within + 10.0 * std::pow((u - tip) / 0.06, 2));
      }
      toes += 12.0 * bell(0.80, 0.04, u);
      double z;
      if (u < 0.24) z = heel;
      else if (u < 0.34) z = lerp(std::min(heel, mid + 6.0), mid, smoothstep(0.24, 0.34, u));
      else if (u < 0.60) z = mid;
      else if (u < 0.66) z = lerp(mid, mth, smoothstep(0.60, 0.66, u));
      else if (u < 0.77) z = mth;
      else z = std::min(mth + 12.0 * bell(0.80, 0.04, u), toes);
      if (u >= 0.66 && u < 0.77) z = std::min(z, mid + 10.0);
      s.height_m[std::size_t(i) * s.nv + j] = float(std::max(0.0, z) / 1000.0);
    }
  }
  return s;
}

}  // namespace ptnet::detail
