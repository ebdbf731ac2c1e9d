"""ptnet_torch.load against hostile weights files: ptnet's own exports load
with torch.load(weights_only=True) and match the digest config.json records;
a pickled object that would run code is refused without running; weights
scaled, non-finite, a negative BatchNorm variance or an out-of-range scalar
are ValueErrors naming the file and the tensor (issue 24, probe defect 2)."""
import os
import shutil
import unittest

from common import MODELS, cli, fixture, torch_or_skip, workdir


class Payload:
    """What a hostile weights file holds: unpickling it runs a shell command."""

    def __init__(self, marker):
        self.marker = marker

    def __reduce__(self):
        return os.system, (f"touch '{self.marker}'",)


class TorchLoadTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.torch = torch_or_skip()
        import ptnet_torch
        cls.pt = ptnet_torch
        cls.dir = workdir("torch_load")
        cls.weights = {}
        for model in MODELS:
            path = cls.weights[model] = os.path.join(cls.dir, model + ".pt")
            cli("export", "--model", fixture(model), "--out", path, "--force")

    def exported(self, model):
        return self.torch.load(self.weights[model], weights_only=True)

    def save(self, name, sd):
        path = os.path.join(self.dir, name + ".pt")
        self.torch.save(sd, path)
        return path

    def assertRefused(self, model, path, *phrases):
        with self.assertRaises(ValueError) as ctx:
            self.pt.load(fixture(model), path)
        message = str(ctx.exception)
        self.assertTrue(message.startswith(str(path) + ": "), message)
        for phrase in phrases:
            self.assertIn(phrase, message)
        self.assertNotIn("\n", message)

    def test_own_exports_load_with_weights_only_and_match_the_digest(self):
        for model in MODELS:
            with self.subTest(model=model):
                sd = self.exported(model)
                self.assertIsInstance(sd, dict)
                net, cfg = self.pt.load(fixture(model), self.weights[model])
                self.assertEqual(self.pt.weights_digest(net), cfg["integrity"]["model.pt"])

    def test_a_pickled_command_does_not_run(self):
        marker = os.path.join(self.dir, "ran")
        if os.path.exists(marker):
            os.remove(marker)
        sd = self.exported("faithful")
        sd["conv1.weight"] = Payload(marker)
        path = self.save("payload", sd)
        self.assertRefused("faithful", path, "not a plain dict of tensors", "weights_only")
        self.assertFalse(os.path.exists(marker), "loading the file ran its command")

    def test_bad_weights_are_refused_naming_the_tensor(self):
        torch = self.torch
        cases = [  # model, tensor, how it is spoiled, what the message says
            ("faithful", "conv2.weight", lambda t: t.fill_(float("nan")), "non-finite"),
            ("faithful", "fc_latent.bias", lambda t: t.fill_(float("inf")), "non-finite"),
            ("skip", "bn2.running_mean", lambda t: t.fill_(float("-inf")), "non-finite"),
            ("residual", "dbn3.running_var", lambda t: t.neg_().sub_(1e-3), "negative BatchNorm variance"),
            ("frame", "frame.norm1.running_var", lambda t: t.sub_(t.max() + 1), "negative BatchNorm variance"),
            ("frame", "contact_floor", lambda t: t.fill_(1e30), "expected a value in [0, 1]"),
            ("frame", "contact_floor", lambda t: t.fill_(-0.5), "expected a value in [0, 1]"),
            ("faithful", "bn1.num_batches_tracked", lambda t: t.fill_(-1), "is negative"),
        ]
        for i, (model, name, spoil, phrase) in enumerate(cases):
            with self.subTest(model=model, tensor=name, phrase=phrase):
                sd = self.exported(model)
                with torch.no_grad():
                    spoil(sd[name])
                self.assertRefused(model, self.save(f"bad{i}", sd), f"'{name}'", phrase)
                # Also as a state dict in memory (values checked, no digest).
                with self.assertRaises(ValueError) as ctx:
                    self.pt.load(fixture(model), sd)
                self.assertIn(f"'{name}'", str(ctx.exception))

    def test_scaled_weights_do_not_match_the_recorded_digest(self):
        torch = self.torch
        for model in ("faithful", "frame"):
            with self.subTest(model=model):
                sd = self.exported(model)
                with torch.no_grad():
                    for t in sd.values():
                        if t.is_floating_point():
                            t.mul_(10)
                path = self.save(model + "_x10", sd)
                self.assertRefused(model, path, "do not match the digest", os.path.join(fixture(model), "config.json"))
                # Another model's own export does not pass for this one either.
                other = "skip" if model == "faithful" else "frame_context"
                with self.assertRaises(ValueError):
                    self.pt.load(fixture(model), self.weights[other])

    def test_names_and_shapes(self):
        sd = self.exported("faithful")
        sd["extra"] = sd["conv1.bias"].clone()
        self.assertRefused("faithful", self.save("extra", sd), "unexpected tensor 'extra'")
        sd = self.exported("faithful")
        del sd["conv1.bias"]
        self.assertRefused("faithful", self.save("missing", sd), "missing tensor 'conv1.bias'")
        sd = self.exported("faithful")
        sd["conv1.bias"] = sd["conv1.bias"][:-1].clone()
        self.assertRefused("faithful", self.save("shape", sd), "'conv1.bias' has shape")
        self.assertRefused("faithful", self.save("list", [1, 2]), "expected a dict of tensors, found list")

    def test_a_folder_without_a_digest_still_checks_values(self):
        import json
        folder = os.path.join(self.dir, "no_digest")
        shutil.rmtree(folder, ignore_errors=True)
        shutil.copytree(fixture("faithful"), folder)
        cfg_path = os.path.join(folder, "config.json")
        with open(cfg_path) as f:
            cfg = json.load(f)
        cfg.pop("integrity", None)
        with open(cfg_path, "w") as f:
            json.dump(cfg, f)
        sd = self.exported("faithful")
        self.pt.load(folder, self.weights["faithful"])  # no digest recorded: the export loads
        sd["bn3.running_var"][0] = -1.0
        path = self.save("no_digest_bad", sd)
        with self.assertRaises(ValueError) as ctx:
            self.pt.load(folder, path)
        self.assertIn("'bn3.running_var' has a negative BatchNorm variance", str(ctx.exception))


if __name__ == "__main__":
    unittest.main()
