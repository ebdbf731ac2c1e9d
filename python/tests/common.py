"""Shared by the Python tests: the ptnet binary, the fixture folder (models
and data made once by make_fixtures.py), running the CLI."""
import os
import subprocess
import unittest

BINARY = os.environ.get("PTNET_BINARY", "ptnet")
TMP = os.environ.get("PTNET_TEST_TMP", "/tmp/ptnet_python_tests")
FIXTURES = os.path.join(TMP, "fixtures")
TEST_DATA = os.environ.get("PTNET_TEST_DATA", "")
MODELS = ("frame", "frame_context", "faithful", "skip", "residual")
# Seeds of the fixtures' training (make_fixtures.py) and of the weight
# perturbation of test_roundtrip: set them to vary the trained weights,
# since trained weights differ from one CPU to another.
FIXTURE_SEED = int(os.environ.get("PTNET_FIXTURE_SEED", "1"))
PERTURB_SEED = int(os.environ.get("PTNET_PERTURB_SEED", "0"))


def cli(*args, check=True):
    """Runs `ptnet -q ARGS`; returns the CompletedProcess (text)."""
    r = subprocess.run([BINARY, "-q", *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"ptnet {' '.join(map(str, args))} failed ({r.returncode}): {r.stderr}")
    return r


def cli_error(*args):
    """The one-line message of a failing CLI run, without "ptnet: error: "."""
    r = cli(*args, check=False)
    assert r.returncode == 1, (r.returncode, r.stderr)
    line = r.stderr.strip().splitlines()[-1]
    assert line.startswith("ptnet: error: "), line
    return line[len("ptnet: error: "):]


def workdir(name):
    """A fresh folder for one test file."""
    path = os.path.join(TMP, name)
    os.makedirs(path, exist_ok=True)
    return path


def fixture(*parts):
    path = os.path.join(FIXTURES, *parts)
    if not os.path.exists(path):
        raise unittest.SkipTest(f"{path} missing: run the python.make_fixtures test first (ctest -L python)")
    return path


def torch_or_skip():
    try:
        import torch  # noqa: F401
    except ImportError:
        raise unittest.SkipTest("PyTorch is not installed for this Python (Debian: apt install python3-torch); "
                                "the PyTorch interop tests are skipped")
    return torch
