// The evaluation protocol of the paper (eval.hpp): original bodies, same
// motion, seen (take 1) and unseen (take 2) motions, model beside baselines.
#include <algorithm>
#include <map>

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

std::vector<EvalRow> evaluate_pairs(const Dataset& dataset, const TransferFn& model,
                                    const EvaluateOptions& options) {
  const auto pairs = test_pairs(dataset);
  if (pairs.empty())
    throw Error::in(dataset.path(),
                    "no test pairs: evaluation needs the same motion on at least two bodies "
                    "with role 'original'");
  std::vector<EvalRow> rows;
  rows.reserve(pairs.size() * 3);
  int done = 0;
  for (const auto& pair : pairs) {
    const SequenceMeta& src_meta = dataset.sequence(pair.source_sequence);
    const SequenceMeta& dst_meta = dataset.sequence(pair.target_sequence);
    const BodySpec& src_body = dataset.body(src_meta.body_id);
    const BodySpec& dst_body = dataset.body(dst_meta.body_id);
    PressureSequence source = dataset.read(pair.source_sequence);
    PressureSequence truth = dataset.read(pair.target_sequence);
    // Same motion, same frame range: compare over the common length.
    const int frames = std::min(source.frames(), truth.frames());
    source.kpa.resize(std::size_t(frames) * source.mat.cells());
    truth.kpa.resize(std::size_t(frames) * truth.mat.cells());

    const std::pair<std::string, PressureSequence> predictions[] = {
        {"model", model(source, src_body, dst_body)},
        {"copy", copy_baseline(source)},
        {"weight_ratio", weight_ratio_baseline(source, src_body.weight_kg, dst_body.weight_kg)}};
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
    if (options.progress) options.progress(++done, int(pairs.size()));
  }
  return rows;
}

}  // namespace ptnet
