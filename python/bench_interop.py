"""The cost of a call from Python: the calls of bench/bench_interop.cpp made
through the module (JSON on stdout; docs/results.md, "Python interop").

    PYTHONPATH=build/python /usr/bin/python3 python/bench_interop.py [MODEL_DIR] [build/bench/bench_interop]

With the C++ benchmark's path it runs that too (same MODEL_DIR) and prints
the ratio per call."""
import json
import os
import subprocess
import sys
import timeit

import numpy as np

import ptnet


def per_call(fn, min_seconds=1.0):
    """Seconds per call: the best of 3 repeats (C++: the best of 3 repetitions) of enough calls to fill min_seconds."""
    n = 1
    while timeit.timeit(fn, number=n) < min_seconds / 10:
        n *= 4
    return min(timeit.repeat(fn, number=n, repeat=3)) / n


def main():
    model = sys.argv[1] if len(sys.argv) > 1 else None
    walk = ptnet.generate_motion("walking", seconds=4, seed=3)
    body = ptnet.Body("male", 180, 80)
    a, b = np.ones((1, 80, 28), np.float32), np.full((1, 80, 28), 2, np.float32)
    out = {"rmse": per_call(lambda: ptnet.rmse(a, b)),
           "simulate": per_call(lambda: ptnet.simulate(walk, body, seed=1))}
    if model:
        net = ptnet.Transfer(model)
        seq = ptnet.simulate(walk, ptnet.Body("female", 165, 60))
        out["transfer"] = per_call(lambda: net.run(seq, source=("female", 165, 60), target=("male", 185, 95)))
    result = {"python_s_per_call": out}
    if len(sys.argv) > 2:
        env = dict(os.environ, PTNET_BENCH_MODEL=model or "")
        if not model:
            env.pop("PTNET_BENCH_MODEL")
        r = subprocess.run([sys.argv[2], "--benchmark_format=json", "--benchmark_repetitions=3"],
                           capture_output=True, text=True, env=env)
        cpp = {}
        for bm in json.loads(r.stdout)["benchmarks"]:  # the best of the repetitions, as above
            if bm.get("run_type") == "iteration" and not bm.get("error_occurred"):
                scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[bm["time_unit"]]
                name = bm["run_name"].replace("BM_Interop", "").lower()
                cpp[name] = min(cpp.get(name, float("inf")), bm["real_time"] * scale)
        result["cpp_s_per_call"] = cpp
        result["python_minus_cpp_s"] = {k: out[k] - cpp[k] for k in out if k in cpp}
        result["python_over_cpp"] = {k: out[k] / cpp[k] for k in out if k in cpp}
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
