"""ptnet.Transfer.run equals `ptnet transfer` on the same sequence, for every
architecture; the GIL is released while it runs."""
import os
import threading
import time
import unittest

import h5py
import numpy as np

import ptnet
from common import MODELS, cli, fixture, workdir

SEQUENCE = "p1_walking_t1__of01"   # an original body of the fixtures
TARGET = ("male", 185, 95)


class TransferTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = workdir("transfer")
        cls.data = fixture("data.h5")
        with h5py.File(cls.data, "r") as f:
            cls.seq = f["sequences"][SEQUENCE][...]
        cls.source = next(b for b in ptnet.read_bodies_csv(fixture("bodies.csv")) if b.id == "of01")

    def cli_transfer(self, model, *extra):
        out = os.path.join(self.dir, f"{model}{'_'.join(map(str, extra))}.npy")
        cli("transfer", "--model", fixture(model), "--in", self.data, "--sequence", SEQUENCE, "--target",
            ",".join(map(str, TARGET)), "--out", out, "--force", *extra)
        return np.load(out)

    def test_equals_the_cli_for_every_architecture(self):
        for model in MODELS:
            with self.subTest(model=model):
                net = ptnet.Transfer(fixture(model))
                self.assertEqual(net.arch, model.split("_")[0])
                got = net.run(self.seq, source=self.source, target=TARGET)
                want = self.cli_transfer(model)
                self.assertEqual(got.shape, self.seq.shape)
                self.assertTrue(np.array_equal(got, want), f"max diff {np.abs(got - want).max()}")

    def test_options_equal_the_cli_flags(self):
        net = ptnet.Transfer(fixture("faithful"), stride=1, raw=True)
        got = net.run(self.seq, source=(self.source.sex, self.source.height_cm, self.source.weight_kg),
                      target=ptnet.Body(*TARGET))
        self.assertTrue(np.array_equal(got, self.cli_transfer("faithful", "--stride", 1, "--raw")))
        self.assertEqual(net.config["architecture"]["arch"], "faithful")
        self.assertEqual(net.window, 30)

    def test_releases_the_gil(self):
        net = ptnet.Transfer(fixture("faithful"), stride=1)
        long_seq = np.tile(self.seq, (4, 1, 1))
        ticks = []
        stop = threading.Event()

        def tick():
            while not stop.is_set():
                ticks.append(time.perf_counter())
                time.sleep(0.001)

        t = threading.Thread(target=tick)
        t.start()
        start = time.perf_counter()
        net.run(long_seq, source=self.source, target=TARGET)
        end = time.perf_counter()
        stop.set()
        t.join()
        during = [x for x in ticks if start < x < end]
        self.assertGreater(len(during), 3, f"the other thread ran {len(during)} times in {end - start:.3f} s")


if __name__ == "__main__":
    unittest.main()
