// SimSettings -> SimOptions: the one mapping of the simulator's front-end
// settings (sim.hpp), with their defaults and ranges.
#include "ptnet/sim.hpp"

namespace ptnet {

SimSettings::SimSettings()
    : compliance_mm(SimOptions{}.compliance_m * 1000), subsamples(SimOptions{}.subsamples) {}

SimOptions sim_options(const SimSettings& a) {
  const SimSettingsRanges& r = kSimSettingsRanges;
  check_range("rows", a.rows, r.rows);
  check_range("cols", a.cols, r.cols);
  check_range("pitch_m", a.pitch_m, r.pitch_m);
  check_range("compliance_mm", a.compliance_mm, r.compliance_mm);
  check_range("subsamples", a.subsamples, r.subsamples);
  const auto check_override = [](const char* field, const std::optional<double>& v, const Range& range) {
    if (v) check_range(field, *v, range);
  };
  check_override("crosstalk", a.crosstalk, r.crosstalk);
  check_override("saturation_kpa", a.saturation_kpa, r.saturation_kpa);
  check_override("noise_kpa", a.noise_kpa, r.noise_kpa);
  check_override("threshold_kpa", a.threshold_kpa, r.threshold_kpa);
  check_override("quantum_kpa", a.quantum_kpa, r.quantum_kpa);

  SimOptions s;
  s.mat = MatSpec{a.rows, a.cols, a.pitch_m};
  s.placement = parse_placement(a.placement);
  s.compliance_m = a.compliance_mm / 1000.0;
  s.subsamples = a.subsamples;
  if (a.ideal_sensor) s.sensor = ideal_sensor();
  if (a.crosstalk) s.sensor.crosstalk = *a.crosstalk;
  if (a.saturation_kpa) s.sensor.saturation_kpa = *a.saturation_kpa;
  if (a.noise_kpa) s.sensor.noise_sd_kpa = *a.noise_kpa;
  if (a.threshold_kpa) s.sensor.threshold_kpa = *a.threshold_kpa;
  if (a.quantum_kpa) s.sensor.quantum_kpa = *a.quantum_kpa;
  s.seed = a.seed;
  return s;
}

}  // namespace ptnet
