"""The PyTorch modules of ptnet_torch, loaded from `ptnet export`, give ptnet's
output: the forward pass on the same windows and the whole transfer
(alignment, windows, threshold). Both float32 evaluations are compared with
the float64 one within the tolerance error_bound derives (its module
docstring), which a 0.1 % error in one weight exceeds."""
import copy
import os
import unittest

import numpy as np

import ptnet
from common import MODELS, cli, fixture, torch_or_skip, workdir
from error_bound import U, check_within, transfer_bound


def sequence():
    import h5py
    with h5py.File(fixture("data.h5"), "r") as f:
        return f["sequences"]["p1_walking_t1__of01"][...]


class TorchTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.torch = torch_or_skip()
        import ptnet_torch
        cls.pt = ptnet_torch
        cls.dir = workdir("torch")
        cls.seq = sequence()
        cls.source = next(b for b in ptnet.read_bodies_csv(fixture("bodies.csv")) if b.id == "of01")
        cls.target = ("male", 185.0, 95.0)
        cls.weights = {}
        for model in MODELS:
            path = cls.weights[model] = os.path.join(cls.dir, model + ".pt")
            cli("export", "--model", fixture(model), "--out", path, "--force")

    def test_state_dict_has_ptnets_names(self):
        for model in MODELS:
            with self.subTest(model=model):
                sd = self.torch.load(self.weights[model], weights_only=True)
                self.assertIsInstance(sd, dict)
                net = self.pt.PressureTransferNet(self.pt.read_config(fixture(model)))
                self.assertEqual(sorted(sd), sorted(net.state_dict()))
                net.load_state_dict(sd)  # strict: same names and shapes

    def test_forward_on_the_same_windows(self):
        torch = self.torch
        for model in MODELS:
            with self.subTest(model=model):
                net, cfg = self.pt.load(fixture(model), self.weights[model])
                k = cfg["architecture"]["window"]
                scale = cfg["normalisation"]["pressure_scale_kpa"]
                x = self.seq[:3 * k] if k > 1 else self.seq[:40]
                # ptnet: windows every k frames (each frame in one window), raw output.
                ours = ptnet.Transfer(fixture(model), stride=k, raw=True).run(x, source=self.source, target=self.target)
                if cfg["architecture"]["align"] == "zoom":  # the input ptnet's network sees
                    s = self.target[1] / self.source.height_cm
                    x = ptnet.zoom_about_centre(x, s, ptnet.body_gain(self.source.height_cm, self.source.weight_kg,
                                                                      self.target[1], self.target[2]))
                m = self.pt.input_margin(cfg["architecture"])  # each window's context frames beyond its ends
                padded = self.pt.with_margin(torch.from_numpy(x / np.float32(scale)), m)
                windows = torch.stack([padded[s:s + k + 2 * m] for s in range(0, len(x), k)])  # [n,K+2m,H,W]
                n = windows.shape[0]
                sa = torch.from_numpy(self.pt.attributes(cfg, self.source)).expand(n, 3)
                ta = torch.from_numpy(self.pt.attributes(cfg, self.target)).expand(n, 3)
                with torch.no_grad():
                    theirs = net(windows, sa, ta).reshape(x.shape).numpy()
                # The same windows as a transfer with stride k, in float64.
                y = self.seq[:len(x)]
                ref, tol = transfer_bound(net, cfg, y, self.source, self.target, stride=k, raw=True)
                check_within(self, f"{model}: ptnet", ours, ref, tol, scale)
                check_within(self, f"{model}: PyTorch", theirs.astype(np.float64) * scale, ref, tol, scale)
                self.assertGreater(np.abs(theirs).sum(), 0, f"{model}: an all-zero output tests nothing")

    def test_whole_transfer(self):
        for model in MODELS:
            for raw in (False, True):
                with self.subTest(model=model, raw=raw):
                    net, cfg = self.pt.load(fixture(model), self.weights[model])
                    ours = ptnet.Transfer(fixture(model), raw=raw).run(self.seq, source=self.source, target=self.target)
                    theirs = self.pt.transfer(net, cfg, self.seq, self.source, self.target, raw=raw)
                    ref, tol = transfer_bound(net, cfg, self.seq, self.source, self.target, raw=raw)
                    scale = cfg["normalisation"]["pressure_scale_kpa"]
                    check_within(self, f"{model}: ptnet", ours, ref, tol, scale)
                    check_within(self, f"{model}: PyTorch", theirs, ref, tol, scale)

    def test_the_tolerance_catches_a_wrong_weight(self):
        # What these tests guard against: a weight read or folded wrongly. One
        # weight tensor off by 0.1 % moves the output beyond the tolerance.
        torch = self.torch
        for model in MODELS:
            with self.subTest(model=model):
                net, cfg = self.pt.load(fixture(model), self.weights[model])
                wrong = copy.deepcopy(net)
                first = next(p for name, p in wrong.named_parameters() if name.endswith("weight"))
                with torch.no_grad():
                    first.mul_(1.001)
                ref, tol = transfer_bound(net, cfg, self.seq, self.source, self.target, raw=True)
                got = self.pt.transfer(wrong, cfg, self.seq, self.source, self.target, raw=True)
                self.assertTrue(np.any(np.abs(got - ref) > tol), f"{model}: a 0.1 % error passes unseen")

    def test_whole_transfer_with_mirror_averaging(self):
        import json, shutil
        folder = os.path.join(self.dir, "frame_mirror")
        shutil.rmtree(folder, ignore_errors=True)
        shutil.copytree(fixture("frame"), folder)
        with open(os.path.join(folder, "config.json")) as f:
            cfg = json.load(f)
        cfg["architecture"]["mirror"] = True
        with open(os.path.join(folder, "config.json"), "w") as f:
            json.dump(cfg, f)
        net, cfg = self.pt.load(folder, self.weights["frame"])
        ours = ptnet.Transfer(folder, raw=True).run(self.seq, source=self.source, target=self.target)
        plain = ptnet.Transfer(fixture("frame"), raw=True).run(self.seq, source=self.source, target=self.target)
        theirs = self.pt.transfer(net, cfg, self.seq, self.source, self.target, raw=True)
        ref, tol = transfer_bound(net, cfg, self.seq, self.source, self.target, raw=True)
        scale = cfg["normalisation"]["pressure_scale_kpa"]
        check_within(self, "ptnet", ours, ref, tol, scale)
        check_within(self, "PyTorch", theirs, ref, tol, scale)
        self.assertTrue(np.any(np.abs(plain - ref) > tol), "averaging changed nothing")

    def test_zoom_alignment(self):
        # Each output cell is g sum w_r w_c x over four taps; along each term's
        # path: w_r and w_c rounded to float32, two products, three additions,
        # g rounded, one product: 9 roundings, so a float32 zoom lies within
        # gamma(9) g sum |w_r w_c x| (worst case) of the float64 one.
        gamma9 = 9 * U / (1 - 9 * U)
        for s in (0.83, 1.0, 1.17):
            exact = self.pt.zoom_about_centre(self.seq, s, 1.3, dtype=np.float64)
            size = self.pt.zoom_about_centre(np.abs(self.seq), s, 1.3, dtype=np.float64)
            for name, got in (("numpy", self.pt.zoom_about_centre(self.seq, s, 1.3)),
                              ("ptnet", ptnet.zoom_about_centre(self.seq, s, 1.3))):
                check_within(self, f"{name} zoom by {s}", got, exact, gamma9 * size, 1.0)


if __name__ == "__main__":
    unittest.main()
