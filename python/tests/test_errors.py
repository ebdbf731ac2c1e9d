"""Bad input raises ValueError or OSError with the CLI's one-line message."""
import glob
import os
import unittest

import numpy as np

import ptnet
from common import TEST_DATA, cli_error, fixture, workdir


class ErrorTest(unittest.TestCase):
    def assertRaisesLine(self, exc_type, message, fn, *args, **kwargs):
        with self.assertRaises(exc_type) as ctx:
            fn(*args, **kwargs)
        self.assertEqual(str(ctx.exception), message)
        self.assertNotIn("\n", str(ctx.exception))

    def test_missing_files_are_oserror(self):
        d = workdir("errors")
        missing = os.path.join(d, "missing.bvh")
        self.assertRaisesLine(OSError, cli_error("info", missing), ptnet.read_bvh, missing)
        nomodel = os.path.join(d, "no_model")
        out = os.path.join(d, "t.npy")
        seq = os.path.join(d, "seq.npy")
        np.save(seq, np.zeros((30, 80, 28), np.float32))
        want = cli_error("transfer", "--model", nomodel, "--in", seq, "--source", "female,165,60", "--target",
                         "male,180,80", "--out", out)
        self.assertRaisesLine(OSError, want, ptnet.Transfer, nomodel)

    def test_malformed_bvh_is_valueerror_with_the_line(self):
        files = sorted(glob.glob(os.path.join(TEST_DATA, "malformed", "*.bvh")))
        self.assertTrue(files)
        for path in files[:5]:
            with self.subTest(path=os.path.basename(path)):
                self.assertRaisesLine(ValueError, cli_error("info", path), ptnet.read_bvh, path)

    def test_bodies(self):
        self.assertRaisesLine(ValueError, "sex 'giant' is not female or male", ptnet.Body, "giant", 170, 70)
        with self.assertRaises(ValueError):
            ptnet.Body("female", 300, 60)
        net = ptnet.Transfer(fixture("faithful"))
        seq = np.zeros((30, 80, 28), np.float32)
        d = workdir("errors")
        np.save(os.path.join(d, "seq.npy"), seq)
        want = cli_error("transfer", "--model", fixture("faithful"), "--in", os.path.join(d, "seq.npy"), "--source",
                         "female,165,60", "--target", "male,300,80", "--out", os.path.join(d, "t.npy"), "--force")
        self.assertRaisesLine(ValueError, want, net.run, seq, source=("female", 165, 60), target=("male", 300, 80))

    def test_arrays(self):
        net = ptnet.Transfer(fixture("faithful"))
        src, dst = ("female", 165, 60), ("male", 180, 80)
        with self.assertRaises(ValueError) as ctx:
            net.run(np.zeros((30, 80), np.float32), source=src, target=dst)
        self.assertIn("expected a float32 array [T, rows, cols]", str(ctx.exception))
        with self.assertRaises(ValueError) as ctx:
            net.run(np.zeros((10, 80, 28), np.float32), source=src, target=dst)
        self.assertIn("the model's window needs at least 30", str(ctx.exception))
        bad = np.zeros((30, 80, 28), np.float32)
        bad[3, 1, 1] = np.nan
        with self.assertRaises(ValueError) as ctx:
            net.run(bad, source=src, target=dst)
        self.assertIn("non-finite value", str(ctx.exception))
        with self.assertRaises(ValueError) as ctx:
            ptnet.rmse(np.zeros(3, np.float32), np.zeros(4, np.float32))
        self.assertIn("differ in shape", str(ctx.exception))
        with self.assertRaises(ValueError):
            ptnet.generate_motion("dancing")
        with self.assertRaises(ValueError):
            ptnet.simulate(ptnet.generate_motion(seconds=1), ptnet.Body("male", 180, 80), placement="floating")


if __name__ == "__main__":
    unittest.main()
