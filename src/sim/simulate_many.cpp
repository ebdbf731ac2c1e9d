// Many simulations on ptnet::parallel_for; results by job index, so the
// output does not depend on the number of threads or the scheduling.
#include <iterator>
#include <mutex>
#include <optional>

#include "ptnet/error.hpp"
#include "core/parallel.hpp"
#include "ptnet/sim.hpp"
#include "sim/sim_internal.hpp"

namespace ptnet {

std::vector<PressureSequence> simulate_many(const std::vector<SimJob>& jobs,
                                            const SimOptions& options, int threads,
                                            const ProgressFn& progress,
                                            std::vector<std::vector<PressureSequence>>* rereads,
                                            std::vector<ForceTable>* forces) {
  for (const auto& j : jobs)
    if (!j.motion || !j.body) throw Error("simulate_many: a job has no motion or body");
  const int n = int(jobs.size());
  std::vector<PressureSequence> out(static_cast<std::size_t>(n));
  if (rereads) rereads->assign(static_cast<std::size_t>(n), {});
  if (forces) forces->assign(static_cast<std::size_t>(n), {});
  std::mutex mutex;  // serialises the progress callback
  int done = 0;
  parallel_for(n, threads, [&](int i) {
    SimOptions o = options;
    o.seed = jobs[std::size_t(i)].seed;
    const SimJob& job = jobs[std::size_t(i)];
    // One path: the job's seed first, then its rereads (if asked for).
    std::vector<std::uint64_t> seeds{job.seed};
    if (rereads) seeds.insert(seeds.end(), job.reread_seeds.begin(), job.reread_seeds.end());
    std::optional<MotionPlacement> own;
    if (!job.placement) own = place_motion(*job.motion, o);
    const MotionPlacement& place = job.placement ? *job.placement : *own;
    std::vector<FrameTrace> trace;
    std::vector<PressureSequence> reads = simulate_reads(*job.motion, *job.body, o, place, seeds, forces ? &trace : nullptr);
    if (forces) (*forces)[std::size_t(i)] = force_table(trace, *job.motion, *job.body);
    out[std::size_t(i)] = std::move(reads[0]);
    if (rereads)
      (*rereads)[std::size_t(i)].assign(std::make_move_iterator(reads.begin() + 1),
                                        std::make_move_iterator(reads.end()));
    std::lock_guard<std::mutex> lock(mutex);
    ++done;
    if (progress) progress(progress_count("simulate", done, n, "sequences"));
  });
  return out;
}

}  // namespace ptnet
