"""Fixtures of the Python tests, made once (ctest fixture): a small simulated
dataset and one tiny trained model per architecture in $PTNET_TEST_TMP/fixtures."""
import os
import shutil

from common import FIXTURE_SEED, FIXTURES, cli

TRAIN = {"--epochs": 1, "--samples-per-epoch": 48, "--val-samples": 16, "--channels": "4,8,8", "--hidden": 16,
         "--latent": 16, "--threads": 1, "--batch": 16, "--micro-batch": 16,
         "--seed": FIXTURE_SEED}
MODELS = {
    # contact head, zoom alignment, window 1; trained long enough that its
    # contact head predicts contact (8 s)
    "frame": {"--preset": "fast", "--epochs": 2, "--samples-per-epoch": 2048, "--lr": 0.01},
    "frame_context": {"--preset": "fast", "--context": 1, "--window": 4, "--contact-weight": 0, "--align": "none"},
    "faithful": {"--preset": "paper"},
    "skip": {"--preset": "paper", "--arch": "skip"},
    "residual": {"--preset": "paper", "--arch": "residual", "--align": "zoom"},
}


def train_args(options):
    merged = {**TRAIN, **options}
    return [x for kv in merged.items() for x in kv]


if __name__ == "__main__":
    shutil.rmtree(FIXTURES, ignore_errors=True)
    os.makedirs(FIXTURES)
    f = lambda *p: os.path.join(FIXTURES, *p)
    cli("bodies", "--males", 2, "--females", 2, "--originals", "1,1", "--seed", 1, "--out", f("bodies.csv"))
    cli("simulate", "--embedded", "--performers", 1, "--takes", 1, "--seconds", 4, "--bodies", f("bodies.csv"),
        "--out", f("data.h5"), "--threads", 1, "--no-floor")
    for name, args in MODELS.items():
        cli("train", "--data", f("data.h5"), "--out", f(name), *train_args(args))
    print("fixtures in", FIXTURES)
