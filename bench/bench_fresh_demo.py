"""A new user's `make demo`, phase by phase: clones this repository (its
committed HEAD) into a fresh folder and runs there what `make demo` runs,
one phase at a time, with ccache off (a fresh machine has no cache):
`make build-deps` (seconds when everything is present), `make configure`,
the build of `ptnet` (the slowest compilations from Ninja's log), then
`ptnet demo` split at its own messages into simulate (and the figure),
train, evaluate and report. Prints JSON (seconds per phase, wall
and CPU of the build).

    /usr/bin/python3 bench/bench_fresh_demo.py [--keep DIR] [--jobs N]

The figures include whatever else runs on the machine: say so when you
quote them."""
import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmd, cwd, env, log):
    start, cpu = time.monotonic(), cpu_children()
    with open(log, "ab") as out:
        code = subprocess.call(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
    if code != 0:
        sys.exit(f"bench_fresh_demo: {' '.join(cmd)} exited {code}; see {log}")
    return round(time.monotonic() - start, 1), round(cpu_children() - cpu, 1)


def slowest_compilations(build, n=5):
    rows = []
    with open(os.path.join(build, ".ninja_log")) as f:
        for line in f:
            if line.startswith("#"):
                continue
            start, end, _, target, _ = line.rstrip("\n").split("\t")
            if target.endswith(".o"):
                rows.append((round((int(end) - int(start)) / 1000, 1), target))
    rows.sort(reverse=True)
    return {"compilations": len(rows), "slowest_s": [{"s": s, "target": t} for s, t in rows[:n]]}


def run_demo(repo, env, log):
    """ptnet demo, its stderr lines timestamped. Simulation ends at "demo:
    training"; evaluation's lines ("evaluate: D/T pairs", every tenth of the
    pairs off a terminal) give its rate, hence its start and end."""
    start = time.monotonic()
    trained, evals = None, []
    proc = subprocess.Popen(["build/ptnet", "demo", "--out", "demo", "--force"], cwd=repo, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1)
    with open(log, "a") as out:
        for line in proc.stdout:
            out.write(line)
            now = time.monotonic() - start
            if line.startswith("demo: training") and trained is None:
                trained = now
            elif line.startswith("evaluate: "):
                done, total = line.split()[1].split("/")
                evals.append((now, int(done), int(total)))
    if proc.wait() != 0 or trained is None or len(evals) < 2:
        sys.exit(f"bench_fresh_demo: ptnet demo exited {proc.returncode} (or printed no phases); see {log}")
    end = time.monotonic() - start
    (t1, d1, total), (t2, d2, _) = evals[0], evals[-1]
    evaluate = (t2 - t1) * total / (d2 - d1)
    return {"simulate_s": round(trained, 1), "train_s": round(t2 - evaluate - trained, 1),
            "evaluate_s": round(evaluate, 1), "report_s": round(end - t2, 1), "demo_s": round(end, 1)}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--keep", help="work in this new folder and keep it (the clone, its build, the log)")
    p.add_argument("--jobs", type=int, default=os.cpu_count())
    a = p.parse_args()
    source = os.path.dirname(here)
    if a.keep:
        os.makedirs(a.keep)  # refuses a folder that exists
    folder = a.keep or tempfile.mkdtemp(prefix="ptnet-fresh-")
    repo = os.path.join(folder, "ptnet")
    env = dict(os.environ, CCACHE_DISABLE="1")
    log = os.path.join(folder, "fresh-demo.log")  # kept when a phase fails
    subprocess.run(["git", "clone", "-q", source, repo], check=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=repo, capture_output=True,
                            text=True).stdout.strip()
    result = {"commit": commit, "cpus": os.cpu_count()}
    # The Makefile's own steps (make demo = build-deps, configure, the ptnet target, ptnet demo).
    result["deps_s"], _ = timed(["make", "--no-print-directory", "build-deps"], repo, env, log)
    result["configure_s"], _ = timed(["make", "--no-print-directory", "configure"], repo, env, log)
    result["build_s"], result["build_cpu_s"] = timed(["cmake", "--build", "build", "-j", str(a.jobs),
                                                      "--target", "ptnet"], repo, env, log)
    result["build"] = slowest_compilations(os.path.join(repo, "build"))
    result.update(run_demo(repo, env, log))
    result["total_s"] = round(sum(result[k] for k in ("deps_s", "configure_s", "build_s", "demo_s")), 1)
    print(json.dumps(result, indent=1))
    if not a.keep:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
