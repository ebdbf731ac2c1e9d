"""`ptnet simulate`, the whole command (parse, retarget, simulate, compress,
write), on the real-motion corpus: frames per CPU-second (user + sys of the
process and its threads, from wait4), one thread, each run writing a fresh
file. With --baseline, another ptnet binary runs interleaved with it (the
same inputs), so that both see the same machine: on a shared 2-vCPU machine
CPU seconds vary by 10-25 % over minutes. Prints JSON.

    /usr/bin/python3 bench/bench_simulate_cli.py build/ptnet [--baseline OLD_PTNET] [--runs 6]
        [--placement follow] [--clips ../shared/mocap-corpus/clips.csv] [--bodies CSV] [--threads 1]

Default bodies: `ptnet bodies --males 8 --females 8 --originals 2,2 --seed 11`
(20 bodies; docs/simulate.md). Default placement: follow, as the corpus
datasets of docs/results.md (with fixed, frames whose feet are off the mat
cost almost nothing). Exits 2 with a message when the corpus is absent."""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time


def run_once(ptnet, args, out):
    cmd = [ptnet, "--quiet", "simulate", "--clips", args.clips, "--bodies", args.bodies, "--placement",
           args.placement, "--seed", "1", "--threads", str(args.threads), "--out", out, "--force"]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)  # the child's CPU time, its threads included
    wall = time.monotonic() - start
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        sys.exit(f"bench_simulate_cli: {' '.join(cmd)} exited {code}")
    return usage.ru_utime + usage.ru_stime, wall


def frames_of(ptnet, path):
    info = json.loads(subprocess.run([ptnet, "info", path, "--json"], check=True, capture_output=True,
                                     text=True).stdout)
    return info["frames"], info["file_bytes"]


def summary(cpu, walls, frames):
    rates = sorted(frames / c for c in cpu)
    return {"cpu_s": [round(c, 3) for c in cpu], "wall_s": [round(w, 3) for w in walls],
            "cpu_s_median": round(statistics.median(cpu), 3),
            "frames_per_cpu_s_median": round(statistics.median(rates)),
            "frames_per_cpu_s_min": round(rates[0]), "frames_per_cpu_s_max": round(rates[-1])}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("ptnet")
    p.add_argument("--baseline", help="another ptnet binary, run interleaved")
    p.add_argument("--runs", type=int, default=6)
    p.add_argument("--placement", default="follow", choices=["fixed", "follow"])
    p.add_argument("--clips", default=os.path.join(here, "..", "..", "shared", "mocap-corpus", "clips.csv"))
    p.add_argument("--bodies")
    p.add_argument("--threads", type=int, default=1)
    args = p.parse_args()
    if not os.path.exists(args.clips):
        print(f"bench_simulate_cli: {args.clips}: not found (the corpus, ../shared/mocap-corpus); skipped",
              file=sys.stderr)
        sys.exit(2)
    binaries = {"ptnet": args.ptnet}
    if args.baseline:
        binaries["baseline"] = args.baseline
    with tempfile.TemporaryDirectory() as d:
        if not args.bodies:
            args.bodies = os.path.join(d, "bodies.csv")
            subprocess.run([args.ptnet, "--quiet", "bodies", "--males", "8", "--females", "8", "--originals", "2,2",
                            "--seed", "11", "--out", args.bodies], check=True)
        cpu = {k: [] for k in binaries}
        walls = {k: [] for k in binaries}
        for _ in range(args.runs):
            for name, exe in binaries.items():
                c, w = run_once(exe, args, os.path.join(d, name + ".h5"))
                cpu[name].append(c)
                walls[name].append(w)
        frames, size = frames_of(args.ptnet, os.path.join(d, "ptnet.h5"))
        result = {"benchmark": "ptnet simulate, whole command", "clips": os.path.abspath(args.clips),
                  "placement": args.placement, "threads": args.threads, "runs": args.runs, "frames": frames,
                  "file_bytes": size}
        for name in binaries:
            result[name] = summary(cpu[name], walls[name], frames)
        if args.baseline:
            with open(os.path.join(d, "ptnet.h5"), "rb") as a, open(os.path.join(d, "baseline.h5"), "rb") as b:
                result["same_bytes_as_baseline"] = a.read() == b.read()
            result["cpu_ratio_median"] = round(
                statistics.median(n / o for n, o in zip(cpu["ptnet"], cpu["baseline"])), 3)
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
