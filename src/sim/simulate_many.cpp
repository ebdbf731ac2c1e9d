// Many simulations on a pool of std::threads; results by job index, so the
// output does not depend on the number of threads or the scheduling.
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "ptnet/error.hpp"
#include "ptnet/sim.hpp"

namespace ptnet {

std::vector<PressureSequence> simulate_many(const std::vector<SimJob>& jobs,
                                            const SimOptions& options, int threads,
                                            const std::function<void(int, int)>& progress) {
  for (const auto& j : jobs)
    if (!j.motion || !j.body) throw Error("simulate_many: a job has no motion or body");
  const int n = int(jobs.size());
  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min(threads, n));
  std::vector<PressureSequence> out(n);
  std::atomic<int> next{0};
  std::mutex mutex;
  int done = 0;
  std::exception_ptr error;
  auto work = [&] {
    for (;;) {
      int i = next++;
      if (i >= n) return;
      try {
        SimOptions o = options;
        o.seed = jobs[i].seed;
        out[i] = simulate(*jobs[i].motion, *jobs[i].body, o);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        next = n;  // stop handing out work
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done, n);
    }
  };
  if (threads == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (int k = 0; k < threads; ++k) pool.emplace_back(work);
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
  return out;
}

}  // namespace ptnet
