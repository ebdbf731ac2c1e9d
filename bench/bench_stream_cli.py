"""`ptnet stream` end to end at a live rate: frames are written to its stdin
at --fps (default 60) from a thread, the transferred frames read from its
stdout; per-frame latency = time the output frame is read - time its input
frame was written (pipe, parsing, transfer, writing). Prints JSON (p50, p99,
max ms; frames/s achieved). Needs numpy and a model folder:

    /usr/bin/python3 bench/bench_stream_cli.py build/ptnet MODEL_DIR [--fps 60] [--frames 600] [--cpu 0]

Input: a simulated walk (`ptnet simulate --embedded`, 1 performer) when
numpy+h5py are present, else random sparse frames. --cpu N pins ptnet to
one core (taskset) for the "one core" figure."""
import json
import os
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np


def frames_of_walk(ptnet, n):
    try:
        import h5py
    except ImportError:
        rng = np.random.default_rng(0)
        return (rng.random((n, 80, 28), dtype=np.float32) * (rng.random((n, 80, 28)) > 0.9) * 50).astype(np.float32)
    with tempfile.TemporaryDirectory() as d:
        bodies = os.path.join(d, "b.csv")
        with open(bodies, "w") as f:
            f.write("id,sex,height_cm,weight_kg\ns,female,165,60\n")
        out = os.path.join(d, "w.h5")
        subprocess.run([ptnet, "--quiet", "simulate", "--embedded", "--performers", "1", "--takes", "1",
                        "--seconds", str(max(4, n // 30 + 1)), "--bodies", bodies, "--out", out], check=True,
                       stdout=subprocess.DEVNULL)
        with h5py.File(out) as h:
            seqs = [h["sequences"][k][()] for k in h["sequences"]]
    walk = max(seqs, key=lambda s: s.sum())
    return np.ascontiguousarray(np.resize(walk, (n, 80, 28)), dtype=np.float32)


def main():
    args = sys.argv[1:]
    opt = {"--fps": "60", "--frames": "600", "--cpu": None}
    for k in list(opt):
        if k in args:
            i = args.index(k)
            opt[k] = args[i + 1]
            del args[i:i + 2]
    ptnet, model = args[0], args[1]
    fps, n = float(opt["--fps"]), int(opt["--frames"])
    frames = frames_of_walk(ptnet, n)
    cmd = [ptnet, "--quiet", "stream", "--model", model, "--source", "female,165,60", "--target", "male,185,95",
           "--threads", "1"]
    if opt["--cpu"] is not None:
        cmd = ["taskset", "-c", opt["--cpu"]] + cmd
    p = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, bufsize=0)
    sent = [0.0] * n
    frame_bytes = 80 * 28 * 4

    def produce():
        start = time.perf_counter()
        for t in range(n):
            due = start + t / fps
            while time.perf_counter() < due:
                time.sleep(max(0.0, min(0.001, due - time.perf_counter())))
            sent[t] = time.perf_counter()
            p.stdin.write(frames[t].tobytes())
        p.stdin.close()

    writer = threading.Thread(target=produce)
    writer.start()
    latency, got, buf = [], 0, b""
    while True:
        chunk = p.stdout.read(frame_bytes * 64)
        if not chunk:
            break
        now = time.perf_counter()
        buf += chunk
        while len(buf) >= frame_bytes:
            buf = buf[frame_bytes:]
            if got >= 30:  # a window model's first window holds frames back; steady state only
                latency.append(1e3 * (now - sent[got]))
            got += 1
    writer.join()
    rc = p.wait()
    latency.sort()
    at = lambda q: latency[int(q * (len(latency) - 1) + 0.5)]
    print(json.dumps({"frames_in": n, "frames_out": got, "exit": rc, "fps_offered": fps,
                      "latency_p50_ms": at(0.5), "latency_p99_ms": at(0.99), "latency_max_ms": latency[-1],
                      "load": open("/proc/loadavg").read().split()[:3]}, indent=1))


if __name__ == "__main__":
    main()
