"""Bad input raises the exception its error kind names (ValueError,
FileNotFoundError, FileExistsError, OSError) with the CLI's one-line message;
option fields by the library's names ("force"), where the CLI says flags."""
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

    def test_missing_files_are_filenotfounderror(self):
        d = workdir("errors")
        missing = os.path.join(d, "missing.bvh")
        self.assertRaisesLine(FileNotFoundError, cli_error("info", missing), ptnet.read_bvh, missing)
        nomodel = os.path.join(d, "no_model")
        out = os.path.join(d, "t.npy")
        seq = os.path.join(d, "seq.npy")
        np.save(seq, np.zeros((30, 80, 28), np.float32))
        want = cli_error("transfer", "--model", nomodel, "--in", seq, "--source", "female,165,60", "--target",
                         "male,180,80", "--out", out)
        self.assertRaisesLine(FileNotFoundError, want, ptnet.Transfer, nomodel)

    def test_an_existing_output_is_fileexistserror_naming_force(self):
        d = workdir("errors")
        out = os.path.join(d, "exists.pt")
        with open(out, "wb") as f:
            f.write(b"keep")
        model = fixture("faithful")
        self.assertRaisesLine(FileExistsError, f"{out}: exists; pass force to overwrite",
                              ptnet.export_weights, model, out, force=False)
        with open(out, "rb") as f:
            self.assertEqual(f.read(), b"keep")
        # The CLI says the flag.
        self.assertEqual(cli_error("export", "--model", model, "--out", out),
                         f"{out}: exists; pass --force to overwrite")
        weights = os.path.join(d, "exported.pt")
        ptnet.export_weights(model, weights, force=True)
        folder = os.path.join(d, "exists_model")
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, "keep.txt"), "w") as f:
            f.write("keep")
        self.assertRaisesLine(FileExistsError, f"{folder}: exists; pass force to overwrite",
                              ptnet.import_weights, weights, model, folder, force=False)
        self.assertEqual(os.listdir(folder), ["keep.txt"])

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

    def test_bad_arguments_name_themselves_and_their_value(self):
        # Issue 24, probe defect 11: a string height raised RuntimeError
        # "Unable to cast", gain=nan reported the scale, pitch_m=nan said
        # "shapes differ (40 x 80 x 28 vs 40 x 80 x 28)", pitch_m=-1 passed,
        # threshold_kpa=nan gave binary R^2 1.0, height_cm=-5 passed.
        nan = float("nan")
        seq = np.zeros((40, 80, 28), np.float32)
        seq[:, 10:20, 5:9] = 30.0
        net = ptnet.Transfer(fixture("faithful"))
        for field, body, found in (("height_cm", ("female", "165", 60), "str '165'"),
                                   ("weight_kg", ("female", 165, "heavy"), "str 'heavy'")):
            self.assertRaisesLine(ValueError, f"source body: {field}: expected a number, found {found}",
                                  net.run, seq, source=body, target=("male", 180, 80))
        self.assertRaisesLine(ValueError, "target body: height_cm: expected a number, found NoneType None",
                              ptnet.body_scale_baseline, seq, source=("female", 165, 60), target=("male", None, 80))
        self.assertRaisesLine(ValueError, "zoom: gain: expected a finite number >= 0, found nan",
                              ptnet.zoom_about_centre, seq, 1.1, gain=nan)
        self.assertRaisesLine(ValueError, "zoom: gain: expected a finite number >= 0, found -2",
                              ptnet.zoom_about_centre, seq, 1.1, gain=-2)
        self.assertRaisesLine(ValueError, "zoom: scale: expected a finite number > 0, found inf",
                              ptnet.zoom_about_centre, seq, float("inf"))
        for pitch in (nan, -1.0, 0.0):
            self.assertRaisesLine(ValueError, f"compare: pitch_m: expected a cell size > 0 m, found {pitch:g}",
                                  ptnet.compare, seq, seq, pitch_m=pitch)
        for name in ("binary_r2", "contact_iou"):
            for threshold in (nan, -0.5):
                self.assertRaisesLine(ValueError, f"{name}: threshold_kpa: expected a finite number >= 0, found "
                                      f"{threshold:g}", getattr(ptnet, name), seq, seq, threshold_kpa=threshold)
        self.assertRaisesLine(ValueError, "binary_r2: threshold_kpa: expected a finite number >= 0, found nan",
                              ptnet.compare, seq, seq, threshold_kpa=nan)
        for height in (-5.0, 20.0, nan):
            self.assertRaisesLine(ValueError, "generate_motion: height_cm: expected 0 (the performer's own) or a "
                                  f"height in [50, 250] cm, found {height:g}", ptnet.generate_motion, seconds=1,
                                  height_cm=height)
        # Issue 40, defect 7: readings no mat makes were transferred (3e38 kPa
        # to zeros, negative kPa silently); NaN made rmse NaN; fps=nan kept
        # the file's rate; a message said "pressure: pressure: ...".
        for value, text in ((3e38, "3e+38"), (-0.5, "-0.5")):
            bad = seq.copy()
            bad[2, 1, 1] = value
            self.assertRaisesLine(ValueError, f"transfer: the source sequence: {text} kPa in frame 2, outside "
                                  "[0, 1000000] kPa", net.run, bad, source=("female", 165, 60),
                                  target=("male", 180, 80))
        bad = seq.copy()
        bad[3, 1, 1] = nan
        self.assertRaisesLine(ValueError, "pressure: non-finite value (NaN or Inf) in frame 3", net.run, bad,
                              source=("female", 165, 60), target=("male", 180, 80))
        self.assertRaisesLine(ValueError, "rmse: predicted: non-finite value (NaN or Inf) at index 1",
                              ptnet.rmse, np.array([0, nan], np.float32), np.zeros(2, np.float32))
        self.assertRaisesLine(ValueError, "binary_r2: truth: non-finite value (NaN or Inf) at index 0",
                              ptnet.binary_r2, np.zeros(2, np.float32), np.array([float("inf"), 0], np.float32))
        bvh = os.path.join(TEST_DATA, "bvh", "tpose_cmu_small.bvh")
        for fps in (nan, float("inf")):
            self.assertRaisesLine(ValueError, f"fps: {fps:g} is not in (0, 4000]", ptnet.read_bvh, bvh, fps=fps)
        # The good values still work.
        self.assertEqual(ptnet.compare(seq, seq)["binary_r2"], 1.0)
        self.assertEqual(len(ptnet.generate_motion(seconds=1, height_cm=0)), 30)


if __name__ == "__main__":
    unittest.main()
