// report_test_util.hpp: the small dataset file of the report-page tests:
// synthetic blobs (train_synthetic.hpp) on a 16 x 8 mat, 96 frames per
// sequence, every category seen and unseen.
#pragma once

#include <string>
#include <vector>

#include "data_test_util.hpp"
#include "ptnet/data.hpp"
#include "train_synthetic.hpp"

namespace ptnet::testing {

inline const char* const kReportCategories[] = {"walking", "rom", "freestyle", "acting"};

// 4 retargeted bodies (training) and 2 original ones (test pairs); per
// category one take-1 and one take-2 motion on every body; 16 x 8 mat. The
// original bodies' sequences have noise-floor copies (the pressed cells
// 0.05 kPa higher), so that reports have every method a simulated dataset
// gives them.
inline void write_report_dataset(const std::string& path) {
  const MatSpec mat{kSynthRows, kSynthCols, 0.02};
  DatasetInfo info;
  info.mat = mat;
  info.generator = "report page tests";
  std::vector<BodySpec> bodies;
  for (int b = 0; b < 6; ++b)
    bodies.push_back(BodySpec{(b < 4 ? "r" : "o") + std::to_string(b),
                              b % 2 ? Sex::male : Sex::female, 152.0 + 7 * b,
                              50.0 + 9 * ((b * 5) % 6), b < 4 ? "retargeted" : "original"});
  DatasetWriter w(path, info, bodies, false);
  int motion = 0;
  for (int take : {1, 2})
    for (const char* category : kReportCategories) {
      for (const auto& body : bodies) {
        SequenceMeta m = testing_util::meta_for(std::string(category) + "_t" + std::to_string(take),
                                                body.id, take, category);
        const PressureSequence s = synth_sequence(motion, body, 96, mat);
        w.add(m, s);
        if (body.role == "original") {
          PressureSequence floor = s;
          for (float& v : floor.kpa) v += v > 0 ? 0.05f : 0.0f;
          w.add_floor(m.name, floor);
        }
      }
      ++motion;
    }
  w.commit();
}

}  // namespace ptnet::testing
