"""Python gets the library's option rules, the same as the CLI: one mapping
of the simulator's settings with their ranges, and training's checks
(resume excludes init, a contact weight needs the frame network, ranges),
made before any data is read."""
import os
import unittest

import ptnet
from common import cli_error, workdir


class TrainOptionsTest(unittest.TestCase):
    def setUp(self):
        self.dir = workdir("options")
        self.data = os.path.join(self.dir, "never_read.h5")  # the checks come first
        self.out = os.path.join(self.dir, "model")

    def assertRejected(self, message, cli_message, cli_args, **kwargs):
        with self.assertRaises(ValueError) as ctx:
            ptnet.train(self.data, self.out, **kwargs)
        self.assertEqual(str(ctx.exception), message)
        self.assertFalse(os.path.exists(self.out))
        self.assertEqual(cli_error("train", "--data", self.data, "--out", self.out, *cli_args), cli_message)

    def test_resume_excludes_init(self):
        self.assertRejected("resume and init exclude each other", "--resume and --init exclude each other",
                            ["--resume", "--init", self.dir], resume=True, init=self.dir)

    def test_a_contact_weight_needs_the_frame_network(self):
        want = "model: a contact head needs the frame architecture, found faithful"
        self.assertRejected(want, want, ["--contact-weight", "0.1"], preset="paper", contact_weight=0.1)
        # An architecture switch drops the preset's head; a weight given with it asks for one again.
        self.assertRejected(want, want, ["--preset", "fast", "--arch", "faithful", "--contact-weight", "0.05"],
                            preset="fast", arch="faithful", contact_weight=0.05)

    def test_ranges_name_the_field(self):
        with self.assertRaises(ValueError) as ctx:
            ptnet.train(self.data, self.out, preset="fast", epochs=0)
        self.assertEqual(str(ctx.exception), "epochs: 0 is not in [1, 1000000]")
        with self.assertRaises(ValueError) as ctx:
            ptnet.train(self.data, self.out, preset="fast", lr=float("nan"))
        self.assertEqual(str(ctx.exception), "lr: nan is not in (0, 10]")
        with self.assertRaises(ValueError) as ctx:
            ptnet.train(self.data, self.out, preset="nope")
        self.assertEqual(str(ctx.exception), 'preset: expected paper, fast or full, found "nope"')

    def test_every_override_is_a_keyword(self):
        # Each field of TrainOverrides, as the CLI's flags: micro_batch and
        # align reach the library's checks; an unknown keyword is a TypeError.
        with self.assertRaises(ValueError) as ctx:
            ptnet.train(self.data, self.out, preset="fast", micro_batch=0, mirror=True, align="zoom")
        self.assertEqual(str(ctx.exception), "micro_batch: 0 is not in [1, 1048576]")
        with self.assertRaises(ValueError) as ctx:
            ptnet.train(self.data, self.out, preset="fast", align="tilt")
        self.assertIn("tilt", str(ctx.exception))
        with self.assertRaises(TypeError) as ctx:
            ptnet.train(self.data, self.out, preset="fast", epoch=3)
        self.assertEqual(str(ctx.exception), "train() got an unexpected keyword argument 'epoch'")
        self.assertFalse(os.path.exists(self.out))


class SimulateOptionsTest(unittest.TestCase):
    def test_the_cli_ranges(self):
        m = ptnet.generate_motion("walking", seconds=1)
        body = ptnet.Body("male", 180, 80)
        for kwargs, message in [({"crosstalk": 0.3}, "crosstalk: 0.3 is not in [0, 0.24]"),
                                ({"saturation_kpa": 0.0}, "saturation_kpa: 0 is not in (0, 1000000]"),
                                ({"rows": 0}, "rows: 0 is not in [1, 1000]"),
                                ({"compliance_mm": 0.5}, "compliance_mm: 0.5 is not in [1, 50]"),
                                ({"placement": "moving"}, "placement 'moving' is not fixed or follow")]:
            with self.subTest(**kwargs):
                with self.assertRaises(ValueError) as ctx:
                    ptnet.simulate(m, body, **kwargs)
                self.assertEqual(str(ctx.exception), message)


if __name__ == "__main__":
    unittest.main()


class BaselineTest(unittest.TestCase):
    """A model no better than the all-zero or copy baseline on validation (a
    learning rate that leaves its initial weights): a UserWarning and the
    result's "warning"; with strict=True a ValueError, the folder kept."""

    def test_a_useless_model_is_said_so(self):
        from common import fixture
        data = fixture("data.h5")
        out = os.path.join(workdir("baselines"), "model")
        args = dict(preset="fast", epochs=1, samples_per_epoch=32, val_samples=16, channels=(4, 8, 8), hidden=16,
                    latent=16, threads=1, lr=1e-9, force=True)
        with self.assertWarns(UserWarning) as w:
            result = ptnet.train(data, out, **args)
        self.assertTrue(result["warning"].startswith("validation RMSE "), result["warning"])
        self.assertIn("all-zero baseline", result["warning"])
        self.assertIn("copy baseline", result["warning"])
        self.assertEqual(str(w.warning), f"{out}: {result['warning']}")
        with self.assertRaises(ValueError) as ctx:
            ptnet.train(data, out, strict=True, **args)
        self.assertEqual(str(ctx.exception), f"{out}: {result['warning']} (strict; the folder is kept)")
        self.assertTrue(os.path.exists(os.path.join(out, "model.pt")))
