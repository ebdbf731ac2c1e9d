// core/parallel.hpp: the project's one thread pool loop (internal to the
// library: the stages include it through their private include path).
//
//   std::vector<double> out(n);
//   ptnet::parallel_for(n, threads, [&](int i) { out[i] = work(i); });
//
// Runs f(i) for every i in [0, n) on `threads` std::threads (<= 0: hardware
// concurrency), handing out indices one at a time. After a failure no new
// index starts; the exception of the lowest failing index is rethrown, so the
// error does not depend on scheduling. Results written by index are the same
// whatever the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "ptnet/io.hpp"  // max_threads

namespace ptnet {

template <class F>
void parallel_for(int n, int threads, F f) {
  if (n <= 0) return;
  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min(threads, n));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(n));
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  auto work = [&] {
    for (int i; !failed && (i = next++) < n;) {
      try {
        f(i);
      } catch (...) {
        errors[std::size_t(i)] = std::current_exception();
        failed = true;
      }
    }
  };
  if (threads == 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (int k = 0; k < threads; ++k) pool.emplace_back(work);
    for (auto& t : pool) t.join();
  }
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace ptnet
