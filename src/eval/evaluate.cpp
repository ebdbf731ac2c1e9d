// The evaluation protocol of the paper (eval.hpp): original bodies, same
// motion, seen (take 1) and unseen (take 2) motions, model beside baselines.
#include <algorithm>
#include <map>

#include "eval/eval_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"

namespace ptnet {

std::vector<TestPair> test_pairs(const Dataset& dataset) {
  // motion_id -> sequences on original bodies (sorted by name).
  std::map<std::string, std::vector<const SequenceMeta*>> by_motion;
  for (const auto& s : dataset.sequences())
    if (dataset.body(s.body_id).role == "original") by_motion[s.motion_id].push_back(&s);
  std::vector<TestPair> pairs;
  for (auto& [motion, seqs] : by_motion) {
    std::sort(seqs.begin(), seqs.end(),
              [](const SequenceMeta* a, const SequenceMeta* b) { return a->name < b->name; });
    for (const SequenceMeta* src : seqs)
      for (const SequenceMeta* dst : seqs)
        if (src->body_id != dst->body_id)
          pairs.push_back({motion, src->category, src->take, src->name, dst->name});
  }
  return pairs;
}

PairData load_pair(const Dataset& dataset, const TestPair& pair) {
  PairData d;
  d.source_body = dataset.body(dataset.sequence(pair.source_sequence).body_id);
  d.target_body = dataset.body(dataset.sequence(pair.target_sequence).body_id);
  d.source = dataset.read(pair.source_sequence);
  d.truth = dataset.read(pair.target_sequence);
  const int frames = std::min(d.source.frames(), d.truth.frames());
  d.source.kpa.resize(std::size_t(frames) * d.source.mat.cells());
  d.truth.kpa.resize(std::size_t(frames) * d.truth.mat.cells());
  return d;
}

std::vector<EvalRow> evaluate_pairs(const Dataset& dataset, const TransferFn& model,
                                    const EvaluateOptions& options) {
  const auto pairs = test_pairs(dataset);
  if (pairs.empty())
    throw Error::in(dataset.path(),
                    "no test pairs: evaluation needs the same motion on at least two bodies "
                    "with role 'original'");
  std::vector<EvalRow> rows;
  rows.reserve(pairs.size() * 5);
  int done = 0;
  for (const auto& pair : pairs) {
    const PairData data = load_pair(dataset, pair);
    const PressureSequence& source = data.source;
    const PressureSequence& truth = data.truth;
    const BodySpec& src_body = data.source_body;
    const BodySpec& dst_body = data.target_body;
    const int frames = truth.frames();

    std::vector<std::pair<std::string, PressureSequence>> predictions;
    PressureSequence raw = model(source, src_body, dst_body);
    if (options.model_threshold_kpa > 0) {
      PressureSequence thresholded = raw;
      zero_below(thresholded, options.model_threshold_kpa);
      predictions.emplace_back("model", std::move(thresholded));
      predictions.emplace_back("model_raw", std::move(raw));
    } else {
      predictions.emplace_back("model", std::move(raw));
    }
    predictions.emplace_back("copy", copy_baseline(source));
    predictions.emplace_back("weight_ratio", weight_ratio_baseline(source, src_body.weight_kg, dst_body.weight_kg));
    predictions.emplace_back("body_scale", body_scale_baseline(source, src_body, dst_body));
    if (dataset.sequence(pair.target_sequence).floor) {
      // The noise floor: the truth simulated again with another sensor seed.
      PressureSequence floor = dataset.read_floor(pair.target_sequence);
      floor.kpa.resize(truth.kpa.size());
      predictions.emplace_back("floor", std::move(floor));
    }
    for (const auto& [method, predicted] : predictions) {
      EvalRow r;
      r.method = method;
      r.motion_id = pair.motion_id;
      r.category = pair.category;
      r.take = pair.take;
      r.source_sequence = pair.source_sequence;
      r.target_sequence = pair.target_sequence;
      r.source_body = src_body.id;
      r.target_body = dst_body.id;
      r.frames = frames;
      r.metrics = compare(predicted, truth, options.metrics);
      rows.push_back(std::move(r));
    }
    if (options.progress) options.progress(progress_count("evaluate", ++done, int(pairs.size()), "pairs"));
  }
  return rows;
}

}  // namespace ptnet
