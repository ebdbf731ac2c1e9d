"""The PyTorch side of bench_model: the same networks (python/ptnet_torch.py,
the layers of src/model/model.cpp) timed in Python PyTorch, one thread.
Prints JSON: windows/s of inference (eval mode, inference_mode) and of one
Adam training step, and the single-window latency, keyed as
bench/compare_python.py expects ("inference/W/N", "latency_ms/W",
"train/W/N"; W: 0 = paper widths, 1 = 16/32/64, 2 = the fast preset's frame
network). Run with Debian's /usr/bin/python3 (python3-torch):

    /usr/bin/python3 bench/bench_inference.py [--quick]"""
import json
import os
import sys
import time

import torch

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import ptnet_torch as pt  # noqa: E402

CONFIGS = {
    0: {"arch": "faithful", "window": 30, "rows": 80, "cols": 28, "channels": [64, 128, 256], "hidden": 128, "latent": 128},
    1: {"arch": "faithful", "window": 30, "rows": 80, "cols": 28, "channels": [16, 32, 64], "hidden": 128, "latent": 128},
    2: {"arch": "frame", "window": 1, "rows": 80, "cols": 28, "channels": [16, 32, 48], "hidden": 64, "latent": 128,
        "context": 0, "contact": True},
}


def seconds_per_call(fn, min_seconds):
    """Median seconds of one call over enough calls to fill min_seconds (after 2 warm-up calls)."""
    fn()
    fn()
    times = []
    start = time.perf_counter()
    while time.perf_counter() - start < min_seconds or len(times) < 3:
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    times.sort()
    return times[len(times) // 2]


def eval_net(cfg):
    torch.manual_seed(0)
    net = pt.PressureTransferNet(cfg)
    net.train()
    with torch.no_grad():
        net(torch.rand(4, cfg["window"], 80, 28), torch.randn(4, 3), torch.randn(4, 3))
    return net.eval()


def main():
    quick = "--quick" in sys.argv
    torch.set_num_threads(1)
    min_s = 0.5 if quick else 1.0
    out = {}
    for w, cfg in CONFIGS.items():
        net = eval_net(cfg)
        with torch.inference_mode():
            x = torch.rand(64, cfg["window"], 80, 28)
            a = torch.randn(1, 3).expand(64, 3)
            out[f"inference/{w}/64"] = 64 / seconds_per_call(lambda: net(x, a, a), min_s)
            x1, a1 = x[:1].contiguous(), a[:1].contiguous()
            out[f"latency_ms/{w}"] = 1e3 * seconds_per_call(lambda: net(x1, a1, a1), min_s)
        net.train()
        opt = torch.optim.Adam(net.parameters(), lr=1e-3)
        for n in (8, 16, 32, 64):
            x = torch.rand(n, cfg["window"], 80, 28)
            y = torch.rand(n, cfg["window"], 80, 28)
            a = torch.randn(n, 3)

            def step():
                opt.zero_grad()
                loss = torch.nn.functional.mse_loss(net(x, a, a), y)
                loss.backward()
                opt.step()
            out[f"train/{w}/{n}"] = n / seconds_per_call(step, min_s)
    print(json.dumps({"python_torch": torch.__version__, "threads": torch.get_num_threads(), "results": out}, indent=1))


if __name__ == "__main__":
    main()
