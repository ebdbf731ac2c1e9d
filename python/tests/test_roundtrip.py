"""PyTorch -> ptnet: weights changed in PyTorch, saved with
ptnet_torch.save_state_dict, become a ptnet model folder (ptnet
import-weights) that transfers as the PyTorch module does; exporting that
folder gives the same state dict back. Outputs are compared with the
float64 evaluation within the tolerance error_bound derives (rounding, and the
near-ties of max pooling the perturbed weights create: their module
docstring)."""
import json
import os
import unittest

import numpy as np

import ptnet
from common import MODELS, PERTURB_SEED, cli, cli_error, fixture, torch_or_skip, workdir
from error_bound import check_within, transfer_bound


class RoundTripTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.torch = torch = torch_or_skip()
        import ptnet_torch
        cls.pt = ptnet_torch
        cls.dir = workdir("roundtrip")
        import h5py
        with h5py.File(fixture("data.h5"), "r") as f:
            cls.seq = f["sequences"]["p1_walking_t1__of01"][...]
        cls.source, cls.target = ("female", 177.2, 66.6), ("male", 160.0, 55.0)
        cls.nets = {}
        torch.manual_seed(PERTURB_SEED)
        for model in MODELS:
            exported = os.path.join(cls.dir, model + "_exported.pt")
            cli("export", "--model", fixture(model), "--out", exported, "--force")
            net, cfg = ptnet_torch.load(fixture(model), exported)
            with torch.no_grad():  # "fine-tuning": every weight moved
                for p in net.parameters():
                    p.add_(0.05 * torch.randn_like(p))
                if hasattr(net, "contact_floor"):
                    net.contact_floor.fill_(0.01)
            cls.nets[model] = (net, cfg)
            tuned = os.path.join(cls.dir, model + "_tuned.pt")
            ptnet_torch.save_state_dict(net, tuned)
            cli("import-weights", "--weights", tuned, "--config", fixture(model), "--out",
                os.path.join(cls.dir, model), "--force")

    def test_imported_model_transfers_as_pytorch_does(self):
        for model in MODELS:
            with self.subTest(model=model):
                net, cfg = self.nets[model]
                ours = ptnet.Transfer(os.path.join(self.dir, model)).run(self.seq, source=self.source,
                                                                       target=self.target)
                theirs = self.pt.transfer(net, cfg, self.seq, self.source, self.target)
                ref, tol = transfer_bound(net, cfg, self.seq, self.source, self.target)
                scale = cfg["normalisation"]["pressure_scale_kpa"]
                check_within(self, f"{model}: ptnet", ours, ref, tol, scale)
                check_within(self, f"{model}: PyTorch", theirs, ref, tol, scale)
                before = ptnet.Transfer(fixture(model)).run(self.seq, source=self.source, target=self.target)
                self.assertFalse(np.array_equal(before, ours), "the tuned weights changed nothing")

    def test_export_gives_the_same_state_dict_back(self):
        torch = self.torch
        for model in MODELS:
            with self.subTest(model=model):
                path = os.path.join(self.dir, model + "_again.pt")
                ptnet.export_weights(os.path.join(self.dir, model), path, force=True)
                back = torch.load(path, weights_only=True)
                sd = self.nets[model][0].state_dict()
                self.assertEqual(sorted(back), sorted(sd))
                for k, v in sd.items():
                    self.assertTrue(torch.equal(back[k], v), k)

    def test_config_says_where_the_weights_came_from(self):
        with open(os.path.join(self.dir, "frame", "config.json")) as f:
            cfg = json.load(f)
        with open(fixture("frame", "config.json")) as f:
            original = json.load(f)
        self.assertEqual(cfg["architecture"], original["architecture"])
        self.assertEqual(cfg["normalisation"], original["normalisation"])
        self.assertTrue(cfg["metrics"]["imported_from"].endswith("frame_tuned.pt"))
        self.assertIn("model.pt", cfg["integrity"])
        self.assertNotEqual(cfg["integrity"]["model.pt"], original["integrity"]["model.pt"])

    def test_an_ordered_dict_is_a_clear_error(self):
        # LibTorch 1.13's unpickler cannot read the OrderedDict (with _metadata)
        # of torch.save(net.state_dict()): the message says what to save.
        torch = self.torch
        path = os.path.join(self.dir, "ordered.pt")
        torch.save(self.nets["faithful"][0].state_dict(), path)
        with self.assertRaises(ValueError) as ctx:
            ptnet.import_weights(path, fixture("faithful"), os.path.join(self.dir, "ordered"), force=True)
        self.assertIn("save a plain dict", str(ctx.exception))
        self.assertNotIn("INTERNAL ASSERT", str(ctx.exception))

    def test_mismatched_weights_are_clear_errors(self):
        d = self.dir
        wrong = os.path.join(d, "faithful_tuned.pt")
        msg = cli_error("import-weights", "--weights", wrong, "--config", fixture("skip"), "--out",
                        os.path.join(d, "wrong"), "--force")
        self.assertIn("has shape", msg)
        with self.assertRaises(ValueError) as ctx:
            ptnet.import_weights(wrong, fixture("skip"), os.path.join(d, "wrong"), force=True)
        self.assertEqual(str(ctx.exception), msg)
        msg = cli_error("import-weights", "--weights", wrong, "--config", fixture("frame"), "--out",
                        os.path.join(d, "wrong"), "--force")
        self.assertIn('missing tensor "frame.conv0.weight"', msg)
        torch = self.torch
        extra = dict(self.nets["faithful"][0].state_dict())
        extra["fc.weight"] = torch.zeros(2)
        path = os.path.join(d, "extra.pt")
        torch.save(extra, path)
        with self.assertRaises(ValueError) as ctx:
            ptnet.import_weights(path, fixture("faithful"), os.path.join(d, "wrong"), force=True)
        self.assertIn('unexpected tensor "fc.weight"', str(ctx.exception))
        with self.assertRaises(OSError):
            ptnet.import_weights(os.path.join(d, "none.pt"), fixture("faithful"), os.path.join(d, "wrong"), force=True)
        self.assertFalse(os.path.exists(os.path.join(d, "wrong", "model.pt")))


if __name__ == "__main__":
    unittest.main()
