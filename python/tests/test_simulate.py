"""ptnet.simulate equals `ptnet simulate` for the same clip, body and seed;
motions and bodies as numpy / Python objects."""
import os
import pathlib
import unittest

import h5py
import numpy as np

import ptnet
from common import cli, fixture, workdir

BODIES = "id,sex,height_cm,weight_kg,role\nb1,female,158,55,retargeted\nb2,male,190,95,original\n"


class SimulateTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        d = cls.dir = workdir("simulate")
        cls.bvh = os.path.join(d, "walk.bvh")
        cli("motions", "--category", "walking", "--performer", 2, "--take", 1, "--seconds", 3, "--out", cls.bvh,
            "--force")
        with open(os.path.join(d, "bodies.csv"), "w") as f:
            f.write(BODIES)
        for name, extra in (("fixed", []), ("follow", ["--placement", "follow", "--ideal-sensor"])):
            cli("simulate", "--motions", cls.bvh, "--bodies", os.path.join(d, "bodies.csv"), "--seed", 7,
                "--threads", 1, "--no-floor", "--force", "--out", os.path.join(d, name + ".h5"), *extra)
        cls.bodies = ptnet.read_bodies_csv(os.path.join(d, "bodies.csv"))

    def cli_sequence(self, file, name):
        with h5py.File(os.path.join(self.dir, file), "r") as f:
            return f["sequences"][name][...]

    def test_equals_the_cli_for_every_body(self):
        m = ptnet.read_bvh(self.bvh)
        for body in self.bodies:
            name = f"walk__{body.id}"
            got = ptnet.simulate(m, body, seed=ptnet.sequence_seed(7, name))
            want = self.cli_sequence("fixed.h5", name)
            self.assertEqual(got.dtype, np.float32)
            self.assertEqual(got.shape, want.shape)
            self.assertTrue(np.array_equal(got, want), f"{name}: max diff {np.abs(got - want).max()}")
            self.assertGreater(got.sum(), 0)

    def test_options_equal_the_cli_flags(self):
        m = ptnet.read_bvh(self.bvh)
        body = (self.bodies[1].sex, self.bodies[1].height_cm, self.bodies[1].weight_kg)  # a tuple works too
        got = ptnet.simulate(m, body, seed=ptnet.sequence_seed(7, "walk__b2"), placement="follow", ideal_sensor=True)
        self.assertTrue(np.array_equal(got, self.cli_sequence("follow.h5", "walk__b2")))

    def test_seed_changes_only_the_noise(self):
        m = ptnet.generate_motion("walking", performer=1, take=1, seconds=2, seed=3)
        body = ptnet.Body("male", 180, 80)
        a, b = ptnet.simulate(m, body, seed=1), ptnet.simulate(m, body, seed=2)
        self.assertTrue(np.array_equal(a, ptnet.simulate(m, body, seed=1)))
        self.assertFalse(np.array_equal(a, b))
        self.assertLess(ptnet.rmse(a, b), 1.0)

    def test_motion_is_numpy(self):
        m = ptnet.read_bvh(self.bvh)
        p = m.positions
        self.assertEqual(p.shape, (len(m), 19, 3))
        self.assertEqual(p.dtype, np.float64)
        self.assertFalse(p.flags.writeable)
        self.assertIsNotNone(p.base)  # a view of the motion, not a copy
        self.assertAlmostEqual(m.fps, 30, places=6)
        self.assertEqual(ptnet.Motion.joint_names[0], "pelvis")
        self.assertEqual(len(m.joint_names), 19)
        feet = p[:, [m.joint_names.index("left_ankle"), m.joint_names.index("right_ankle")], 2]
        self.assertLess(feet.min(), 0.15)  # grounded, metres, z up
        tall = m.retarget(190.0)
        self.assertGreater(tall.positions[:, 4, 2].max(), m.positions[:, 4, 2].max())
        g = ptnet.generate_motion("rom", performer=2, take=1, seconds=1.5)
        self.assertEqual((g.name, len(g)), ("p2_rom_t1", 45))

    def test_bodies_equal_the_cli(self):
        mine = ptnet.sample_bodies(males=2, females=2, originals_f=1, originals_m=1, seed=1)
        theirs = ptnet.read_bodies_csv(fixture("bodies.csv"))
        self.assertEqual([(b.id, b.sex, b.height_cm, b.weight_kg, b.role) for b in mine],
                         [(b.id, b.sex, b.height_cm, b.weight_kg, b.role) for b in theirs])

    def test_cover_sampling_reaches_the_tails(self):
        paper = ptnet.sample_bodies(males=8, females=8, seed=1)
        cover = ptnet.sample_bodies(males=8, females=8, seed=1, sampling="cover")
        heights = sorted(b.height_cm for b in cover if b.sex == "female")
        self.assertAlmostEqual(heights[0], 165 - 2.5 * 15 + 0.5 * 75 / 8, places=1)  # the lowest stratum's centre
        self.assertLess(min(b.height_cm for b in cover), min(b.height_cm for b in paper))
        with self.assertRaisesRegex(ValueError, "expected paper or cover"):
            ptnet.sample_bodies(sampling="uniform")

    def test_forces_are_the_pressure_times_the_area(self):
        m = ptnet.read_bvh(self.bvh)
        p, f = ptnet.simulate(m, self.bodies[0], placement="follow", ideal_sensor=True, forces=True)
        self.assertEqual(set(f), {"time_s", "total_n", "left_n", "right_n", "left_cop_u", "right_cop_u"})
        self.assertEqual(f["total_n"].shape, (p.shape[0],))
        # The mat follows the body: every newton of the trace is on the mat.
        on_mat = p.astype(np.float64).sum(axis=(1, 2)) * 0.02 * 0.02 * 1000
        np.testing.assert_allclose(on_mat, f["total_n"], rtol=1e-4, atol=1e-3)
        np.testing.assert_allclose(f["left_n"] + f["right_n"], f["total_n"], rtol=1e-6, atol=1e-6)
        np.testing.assert_allclose(np.diff(f["time_s"]), 1 / 30)
        loaded = f["left_n"] > 0
        self.assertTrue(np.all((f["left_cop_u"][loaded] >= 0) & (f["left_cop_u"][loaded] <= 1)))
        self.assertTrue(np.all(np.isnan(f["left_cop_u"][~loaded])))

    def test_read_motion_reads_markers(self):
        # A standing subject in gait2354 marker names, lab mm, Y up.
        names, at = [], []
        for side, k in (("R.", 1), ("L.", -1)):
            for n, x, y, z in (("ASIS", 120, 1000, 120), ("Heel", -60, 40, 100), ("Toe.Tip", 220, 20, 90),
                               ("Acromium", 0, 1450, 190)):
                names.append(side + n)
                at.append((x, y, k * z))
        names.append("V.Sacral")
        at.append((-100, 1000, 0))
        rows = ["PathFileType\t4\t(X/Y/Z)\ts.trc", "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits",
                f"100\t100\t20\t{len(names)}\tmm", "Frame#\tTime\t" + "\t\t\t".join(names), "", ""]
        for f in range(20):
            rows.append(f"{f + 1}\t{f / 100}\t" + "\t".join(f"{x}\t{y}\t{z}" for x, y, z in at))
        path = os.path.join(self.dir, "stand.trc")
        with open(path, "w") as out:
            out.write("\n".join(rows) + "\n")
        m = ptnet.read_motion(path, fps=0)
        self.assertEqual((len(m), m.fps, m.start_s), (20, 100, 0))
        hips = m.positions[0, [ptnet.Motion.joint_names.index(j) for j in ("left_hip", "right_hip")]]
        self.assertAlmostEqual(np.linalg.norm(hips[0] - hips[1]), 2 * (0.33 * 0.24 + 0.0073), places=6)  # Harrington (markers held as float)
        with self.assertRaisesRegex(ValueError, "stand.trc: marker map .plugin-gait. cannot place the markers: it lacks r_asis"):
            ptnet.read_motion(path, marker_map="plugin-gait")

    def test_paths_may_be_pathlike(self):
        # Before: read_motion(pathlib.Path(...)) raised TypeError (str only).
        bvh = pathlib.Path(self.bvh)
        self.assertEqual(len(ptnet.read_motion(bvh)), len(ptnet.read_motion(self.bvh)))
        self.assertEqual(len(ptnet.read_bvh(bvh)), len(ptnet.read_motion(self.bvh)))
        bodies = ptnet.read_bodies_csv(pathlib.Path(self.dir) / "bodies.csv")
        self.assertEqual([b.id for b in bodies], ["b1", "b2"])
        out = pathlib.Path(self.dir) / "pathlike.bvh"
        ptnet.read_motion(bvh).write_bvh(out, force=True)
        self.assertTrue(out.is_file())
        with self.assertRaisesRegex(ValueError, "expected a .bvh file name"):
            ptnet.read_motion(bvh).write_bvh(pathlib.Path(self.dir) / "walk.trc")

    def test_metrics(self):
        t = np.zeros((2, 80, 28), np.float32)
        t[:, 10:20, 5:9] = 40
        p = t.copy()
        p[0, 10, 5] = 43
        self.assertAlmostEqual(ptnet.rmse(p, t), np.sqrt(9 / t.size), places=6)
        self.assertEqual(ptnet.binary_r2(t, t), 1.0)
        c = ptnet.compare(p, t)
        self.assertEqual(set(c), {"rmse_kpa", "binary_r2", "cop_error_cm", "cop_frames", "force_error_pct",
                                  "contact_iou"})
        self.assertEqual(c["contact_iou"], 1.0)
        z = ptnet.zoom_about_centre(t, 1.0, 2.0)
        self.assertTrue(np.array_equal(z, 2 * t))


if __name__ == "__main__":
    unittest.main()
