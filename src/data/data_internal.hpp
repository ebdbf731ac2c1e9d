// data/data_internal.hpp (private to the data stage; tests and fuzzers
// include it as "data/data_internal.hpp"): the rate rule of a dataset and
// the steps behind the clips list (ptnet/simulate_dataset.hpp).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/rate.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace ptnet {

// A sequence at `fps` belongs in a dataset at `dataset_fps` when
// same_rate(fps, dataset_fps) (core/rate.hpp). DatasetWriter::add requires
// it; simulate_dataset checks every clip before simulating any.

// read_clips_csv on CSV text; files are resolved against `path`'s folder.
std::vector<ClipRow> parse_clips_csv(const std::string& text, const std::string& path);

// A category guessed from a file name: the stem contains walk, rom/range/
// exercise, dance/freestyle or act(ing); "" if none.
std::string category_from_name(const std::string& path);

// A category guessed from the motion itself: "walking" when the pelvis
// travels steadily (mean horizontal speed 0.4-2.5 m/s over a path of
// >= 1.5 m), else "freestyle".
std::string category_from_motion(const Motion& motion);

}  // namespace ptnet
