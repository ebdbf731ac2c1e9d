"""bench_model (C++, LibTorch) and bench_inference.py (Python PyTorch) on the
same networks, interleaved in one run (C++, Python, C++, Python, ...) so
that both see the same machine load; prints JSON with the median of each
figure over the repetitions, the ratio C++ / Python, and the load average
(uptime) before and after. One thread on both sides. Skipped (exit 0, a note
on stderr) when Debian's python3-torch is missing.

The C++ side keeps freed memory (ptnet::keep_freed_memory(), memory.hpp);
the Python side runs with the same glibc malloc settings (GLIBC_TUNABLES:
no mmap below 32 MB, no trim below 1 GiB) unless `--python-malloc default`,
so that the ratio compares the arithmetic, not how often each side faults
fresh pages in (docs/model.md "Speed": on a virtual machine where a page
fault is slow, PyTorch with glibc's defaults is 3-10x slower at batch 64).

    /usr/bin/python3 bench/compare_python.py [build/bench/bench_model] [--reps 3] [--python-malloc kept|default]"""
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CPP_FILTER = ("BM_(InferenceFolded/1/[012]/64|LatencyFolded/1/[012]|Inference/1/[012]|Latency/1/[012]"
              "|TrainStep/1/[012]/(8|16|32|64))/")
ENV = dict(os.environ, OMP_NUM_THREADS="1", MKL_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
# keep_freed_memory()'s settings (src/core/memory.cpp) for the Python side
KEPT_MALLOC = "glibc.malloc.mmap_threshold=33554432:glibc.malloc.trim_threshold=1073741824"


def load():
    return open("/proc/loadavg").read().split()[:3]


def cpp(binary):
    r = subprocess.run([binary, "--benchmark_format=json", "--benchmark_min_time=1",
                        "--benchmark_filter=" + CPP_FILTER], capture_output=True, text=True, env=ENV, check=True)
    out = {}
    for b in json.loads(r.stdout)["benchmarks"]:
        kind, _, widths, *rest = b["run_name"].replace("BM_", "").split("/")
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        if kind == "Latency":
            out[f"latency_ms/{widths}"] = 1e3 * b["real_time"] * scale
        elif kind == "LatencyFolded":  # the median call, as the Python side
            out[f"latency_folded_ms/{widths}"] = b["p50_ms"]
        elif kind == "Inference":
            out[f"inference_module/{widths}/64"] = b["windows_per_s"]
        elif kind == "InferenceFolded":
            out[f"inference/{widths}/{rest[0]}"] = b["windows_per_s"]
        elif kind == "TrainStep":
            out[f"train/{widths}/{rest[0]}"] = b["windows_per_s"]
    return out


def python(kept):
    env = dict(ENV, GLIBC_TUNABLES=KEPT_MALLOC) if kept else ENV
    r = subprocess.run(["/usr/bin/python3", os.path.join(HERE, "bench_inference.py")], capture_output=True,
                       text=True, env=env, check=True)
    return json.loads(r.stdout)["results"]


def main():
    args = [a for a in sys.argv[1:]]
    reps = 3
    if "--reps" in args:
        i = args.index("--reps")
        reps = int(args[i + 1])
        del args[i:i + 2]
    malloc = "kept"
    if "--python-malloc" in args:
        i = args.index("--python-malloc")
        malloc = args[i + 1]
        del args[i:i + 2]
    if malloc not in ("kept", "default"):
        sys.exit(f"compare_python: --python-malloc: expected kept or default, found {malloc}")
    binary = args[0] if args else os.path.join(HERE, "..", "build", "bench", "bench_model")
    if subprocess.run(["/usr/bin/python3", "-c", "import torch"], capture_output=True).returncode != 0:
        print("compare_python: /usr/bin/python3 has no torch (python3-torch): skipped", file=sys.stderr)
        return
    before = load()
    runs_c, runs_p = [], []
    for _ in range(reps):
        runs_c.append(cpp(binary))
        runs_p.append(python(malloc == "kept"))
    med = lambda runs: {k: statistics.median(r[k] for r in runs) for k in runs[0]}
    c, p = med(runs_c), med(runs_p)
    ratio = {}
    for k, v in c.items():
        base = k.replace("latency_folded_ms", "latency_ms").replace("inference_module", "inference")
        if base in p:
            # > 1 means C++ is better (faster throughput, lower latency)
            ratio[k] = p[base] / v if k.startswith("latency") else v / p[base]
    print(json.dumps({"reps": reps, "python_malloc": malloc, "load_before": before, "load_after": load(), "cpp_median": c,
                      "python_median": p, "cpp_over_python": ratio}, indent=1, sort_keys=True))


if __name__ == "__main__":
    main()
