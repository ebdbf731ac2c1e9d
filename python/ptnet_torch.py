"""ptnet_torch: ptnet's PressureTransferNet as PyTorch modules.

The architectures of src/model/model.cpp (faithful, skip, residual, frame) as
torch.nn.Modules whose state_dict() keys and shapes are ptnet's, so that the
weights move both ways:

    import torch, ptnet_torch as pt
    net, cfg = pt.load("model/", "weights.pt")      # ptnet export --model model/ --out weights.pt
    out = pt.transfer(net, cfg, pressure, source=("female", 165, 60), target=("male", 185, 95))
    pt.save_state_dict(net, "tuned.pt")             # ptnet import-weights --weights tuned.pt --config model/ --out tuned/

Dimension legend: N windows, T = window frames (as channels; 30, or 1 for the
fast/full presets' frame network), H x W = mat rows x cols (80 x 28),
A = 3 attributes.

What ptnet does around the network (Transfer::run, src/model/transfer.cpp),
reproduced by transfer() below:
  1. alignment (config "architecture.align" = "zoom" only): each source frame
     zoomed about the mat centre by s = target height / source height
     (bilinear in cell-centre coordinates, cells sampled from outside the mat
     are 0) and multiplied by gain = (target weight / source weight) / s^2;
  2. normalisation: pressure / normalisation.pressure_scale_kpa; attributes
     [sex (female 0, male 1), (height_cm - height_mean_cm) / height_std_cm,
     (weight_kg - weight_mean_kg) / weight_std_kg], float32;
  3. windows of T frames every `stride` frames (plus one ending at the last
     frame); each output frame is the mean of the windows covering it, times
     pressure_scale_kpa; with "architecture.mirror" true, each window's output
     is the mean of the network on the window and, flipped back, on the
     window flipped left-right (the last axis);
  4. cells below normalisation.contact_threshold_kpa set to 0 (unless raw).
"""
import json
import os

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

ATTRIBUTES = 3  # sex, z(height), z(weight)
POOL_LEVELS = 3  # encoder blocks, each halving rows and cols (rounding up)
CONFIG_FILE = "config.json"  # a model folder's files (ModelFiles, include/ptnet/model_config.hpp)
WEIGHTS_FILE = "model.pt"


def read_config(path):
    """config.json of a ptnet model folder (the file or its folder) as a dict."""
    if os.path.isdir(path):
        path = os.path.join(path, CONFIG_FILE)
    with open(path, encoding="utf-8") as f:
        cfg = json.load(f)
    if cfg.get("format") != "ptnet-model":
        raise ValueError(f"{path}: expected format \"ptnet-model\", found {cfg.get('format')!r}")
    return cfg


def _arch(cfg):
    """The "architecture" section of a config.json dict (or that section itself)."""
    return cfg["architecture"] if "architecture" in cfg else cfg


def pooled_size(rows, cols, level):
    for _ in range(level):
        rows, cols = (rows + 1) // 2, (cols + 1) // 2
    return rows, cols


class FrameNet(nn.Module):
    """Arch frame: a conditional U-Net applied to each frame (FrameNetImpl).

    frames [M, 1 + 2 context, H, W], conditions [M, 2A] -> [M, 1 + contact, H, W]."""

    def __init__(self, a):
        super().__init__()
        k = 1 + 2 * a.get("context", 0)
        c1, c2, c3 = a["channels"]
        blocks = [(k, c1), (c1, c2), (c2, c3), (c3, c3), (c2, c2), (c1, c1)]  # enc0 enc1 enc2 mid dec1 dec0
        self.widths, self.offsets, width = [], [], 0
        for i, (cin, cout) in enumerate(blocks):
            setattr(self, f"conv{i}", nn.Conv2d(cin, cout, 3, padding=1, bias=False))
            setattr(self, f"norm{i}", nn.BatchNorm2d(cout, affine=False))
            self.widths.append(cout)
            self.offsets.append(width)
            width += 2 * cout  # gamma, beta
        self.lateral1 = nn.Conv2d(c3, c2, 1)
        self.lateral0 = nn.Conv2d(c2, c1, 1)
        self.head = nn.Conv2d(c1, 2 if a.get("contact", False) else 1, 3, padding=1)
        self.film1 = nn.Linear(2 * ATTRIBUTES, a["hidden"])
        self.film2 = nn.Linear(a["hidden"], width)
        self.pool = nn.MaxPool2d(2, 2, ceil_mode=True)

    def block(self, i, x, film):
        w, o = self.widths[i], self.offsets[i]
        gamma = film[:, o:o + w, None, None]
        beta = film[:, o + w:o + 2 * w, None, None]
        y = getattr(self, f"norm{i}")(getattr(self, f"conv{i}")(x))
        return torch.relu(y * (1 + gamma) + beta)

    def forward(self, frames, conditions):
        film = self.film2(torch.relu(self.film1(conditions)))              # [M, F]
        up = lambda t, like: F.interpolate(t, size=like.shape[2:], mode="nearest")
        e0 = self.block(0, frames, film)                                    # [M,C1,H,W]
        e1 = self.block(1, self.pool(e0), film)                             # [M,C2,H1,W1]
        e2 = self.block(2, self.pool(e1), film)                             # [M,C3,H2,W2]
        m = self.block(3, e2, film)                                         # [M,C3,H2,W2]
        d1 = self.block(4, self.lateral1(up(m, e1)) + e1, film)             # [M,C2,H1,W1]
        d0 = self.block(5, self.lateral0(up(d1, e0)) + e0, film)            # [M,C1,H,W]
        return self.head(d0)                                                # [M,1+contact,H,W]


def frames_with_context(x, context):
    """x [N, T + 2 context, H, W] -> [N*T, 1 + 2 context, H, W]: each of the T
    centre frames with its `context` neighbours on each side (frame_inputs)."""
    n, t, h, w = x.shape[0], x.shape[1] - 2 * context, x.shape[2], x.shape[3]
    if context == 0:
        return x.reshape(n * t, 1, h, w)
    u = x.unfold(1, 2 * context + 1, 1)                                     # [N,T,H,W,K]
    return u.permute(0, 1, 4, 2, 3).reshape(n * t, 2 * context + 1, h, w)


def input_margin(a):
    """Frames of input beyond the output at each end of a window (input_margin):
    a frame network's context, 0 for the window networks. a: the "architecture" section."""
    return a.get("context", 0) if a["arch"] == "frame" else 0


def with_margin(frames, margin):
    """A sequence [T, H, W] with `margin` copies of its first and last frame
    at each end: [T + 2 margin, H, W], the input of a frame model with context."""
    if margin == 0:
        return frames
    return torch.cat([frames[:1].expand(margin, *frames.shape[1:]), frames,
                      frames[-1:].expand(margin, *frames.shape[1:])], 0)


class PressureTransferNet(nn.Module):
    """PressureTransferNetImpl: x [N,T+2 context,H,W] normalised pressure (frame;
    [N,T,H,W] otherwise), source and
    target [N,A] normalised attributes -> [N,T,H,W] normalised pressure >= 0.

    cfg: a config.json dict (read_config) or its "architecture" section."""

    def __init__(self, cfg):
        super().__init__()
        a = _arch(cfg)
        self.arch, self.window, self.rows, self.cols = a["arch"], a["window"], a["rows"], a["cols"]
        self.channels, self.context, self.contact = list(a["channels"]), a.get("context", 0), a.get("contact", False)
        if self.arch not in ("faithful", "skip", "residual", "frame"):
            raise ValueError(f"unknown architecture {self.arch!r}")
        if self.arch == "frame":
            self.frame = FrameNet(a)
            if self.contact:
                self.register_buffer("contact_floor", torch.zeros(()))
            return
        c1, c2, c3 = self.channels
        sf = 2 if self.arch in ("skip", "residual") else 1
        h3, w3 = pooled_size(self.rows, self.cols, POOL_LEVELS)
        flat = c3 * h3 * w3
        self.conv1 = nn.Conv2d(self.window, c1, 3, padding=1)
        self.conv2 = nn.Conv2d(c1, c2, 3, padding=1)
        self.conv3 = nn.Conv2d(c2, c3, 3, padding=1)
        self.bn1, self.bn2, self.bn3 = nn.BatchNorm2d(c1), nn.BatchNorm2d(c2), nn.BatchNorm2d(c3)
        self.pool = nn.MaxPool2d(2, 2, ceil_mode=True, return_indices=True)
        self.fc_features = nn.Linear(flat, a["hidden"])
        self.fc_latent = nn.Linear(a["hidden"] + ATTRIBUTES, a["latent"])
        self.fc_decode = nn.Linear(a["latent"] + ATTRIBUTES, flat)
        self.deconv3 = nn.ConvTranspose2d(c3 * sf, c2, 3, padding=1)
        self.deconv2 = nn.ConvTranspose2d(c2 * sf, c1, 3, padding=1)
        self.deconv1 = nn.ConvTranspose2d(c1 * sf, self.window, 3, padding=1)
        self.dbn3, self.dbn2 = nn.BatchNorm2d(c2), nn.BatchNorm2d(c1)

    def forward_parts(self, x, source, target):
        """(pressure before the output ReLU, contact logits or None), both [N,T,H,W]."""
        n = x.shape[0]
        if self.arch == "frame":
            c = self.context
            t = x.shape[1] - 2 * c                                              # x holds T + 2 context frames
            conditions = torch.cat([source, target], 1).repeat_interleave(t, 0)   # [N*T, 2A]
            out = self.frame(frames_with_context(x, c), conditions)             # [N*T,1+contact,H,W]
            shape = (n, t, x.shape[2], x.shape[3])
            contact = out[:, 1].reshape(shape) if self.contact else None
            return x[:, c:c + t] + out[:, 0].reshape(shape), contact
        skips = self.arch in ("skip", "residual")
        s = [pooled_size(self.rows, self.cols, k) for k in range(POOL_LEVELS + 1)]
        e1 = torch.relu(self.bn1(self.conv1(x)))                                # [N,C1,H,W]
        p1, i1 = self.pool(e1)
        e2 = torch.relu(self.bn2(self.conv2(p1)))                               # [N,C2,H1,W1]
        p2, i2 = self.pool(e2)
        e3 = torch.relu(self.bn3(self.conv3(p2)))                               # [N,C3,H2,W2]
        p3, i3 = self.pool(e3)
        h = torch.relu(self.fc_features(p3.flatten(1)))                         # [N, hidden]
        z = self.fc_latent(torch.cat([h, source], 1))                           # [N, latent]
        d = torch.relu(self.fc_decode(torch.cat([z, target], 1)))
        d = d.view(n, self.channels[2], *s[3])
        d = F.max_unpool2d(d, i3, 2, 2, output_size=s[2])                       # [N,C3,H2,W2]
        if skips:
            d = torch.cat([d, e3], 1)
        d = torch.relu(self.dbn3(self.deconv3(d)))                              # [N,C2,H2,W2]
        d = F.max_unpool2d(d, i2, 2, 2, output_size=s[1])                       # [N,C2,H1,W1]
        if skips:
            d = torch.cat([d, e2], 1)
        d = torch.relu(self.dbn2(self.deconv2(d)))                              # [N,C1,H1,W1]
        d = F.max_unpool2d(d, i1, 2, 2, output_size=s[0])                       # [N,C1,H,W]
        if skips:
            d = torch.cat([d, e1], 1)
        out = self.deconv1(d)                                                   # [N,T,H,W]
        if self.arch == "residual":
            out = out + x
        return out, None

    def forward(self, x, source, target):
        pressure, contact = self.forward_parts(x, source, target)
        if not self.contact:
            return torch.relu(pressure)
        p = torch.maximum(torch.relu(pressure), self.contact_floor)
        return torch.where(contact > 0, p, torch.zeros_like(p))


def save_state_dict(net, path):
    """The module's weights as a plain dict of CPU tensors (what ptnet import-weights reads)."""
    torch.save({k: v.detach().cpu().contiguous() for k, v in net.state_dict().items()}, path)


def load(model_dir, weights):
    """The module of a ptnet model folder with the weights of `weights`, in
    eval mode; and its config.

    `weights` is a path written by ptnet export (or export_weights) from this
    folder, read with torch.load(weights_only=True) (no pickled code runs) and
    checked against the digest config.json records for model.pt (the weights
    ptnet trained: another file, or the same one changed, is refused); or a
    state dict already in memory (e.g. tuned weights: torch.load(path,
    weights_only=True)), whose values are checked but not its digest. Raises
    ValueError naming the file (or "state dict") and the tensor: a missing or
    unexpected tensor or a wrong shape, a non-finite value, a negative
    BatchNorm running variance, a contact_floor outside [0, 1] or a negative
    batch count (check_state_dict)."""
    cfg = read_config(model_dir)
    net = PressureTransferNet(cfg)
    from_file = isinstance(weights, (str, os.PathLike))
    path = os.fspath(weights) if from_file else "state dict"
    sd = read_state_dict(path) if from_file else weights
    check_state_dict(sd, net, path)
    net.load_state_dict(sd)
    if from_file:
        recorded = cfg.get("integrity", {}).get(WEIGHTS_FILE, "")
        found = weights_digest(net)
        if recorded and found != recorded:  # older folders record none (as ptnet does)
            config_path = os.path.join(model_dir, CONFIG_FILE) if os.path.isdir(model_dir) else os.fspath(model_dir)
            raise ValueError(f"{path}: weights do not match the digest in {config_path} ({found}, recorded "
                             f"{recorded}): not exported from this model folder, or changed since")
    return net.eval(), cfg


def read_state_dict(path):
    """The dict of tensors of a file ptnet export wrote, by torch.load with
    weights_only=True: tensors, dicts, lists and numbers are all the
    unpickler builds, so an object whose __reduce__ calls os.system is
    refused (ValueError naming the file) instead of run."""
    import pickle
    try:
        sd = torch.load(path, map_location="cpu", weights_only=True)
    except pickle.UnpicklingError as e:
        why = str(e).rsplit("WeightsUnpickler error: ", 1)[-1].strip().splitlines()[-1]
        raise ValueError(f"{path}: not a plain dict of tensors (refused by torch.load(weights_only=True): {why}; "
                         f"a file exported by an older ptnet must be exported again)") from None
    if not isinstance(sd, dict):
        raise ValueError(f"{path}: expected a dict of tensors, found {type(sd).__name__}")
    return sd


# Largest contact_floor: the floor is the mat's minimum reading over the
# pressure scale (normalisation.min_reading_kpa / pressure_scale_kpa), so it
# lies in [0, 1]; above 1 every contact cell would read more than the scale.
MAX_CONTACT_FLOOR = 1.0


def check_state_dict(sd, net, where):
    """Raises ValueError "WHERE: ..." naming the tensor unless `sd` has
    exactly net's tensor names and shapes, every value finite, every
    BatchNorm running_var >= 0, every num_batches_tracked >= 0 and
    contact_floor in [0, MAX_CONTACT_FLOOR]."""
    expected = net.state_dict()
    for name in sd:
        if name not in expected:
            raise ValueError(f"{where}: unexpected tensor {name!r} (not in the {net.arch} model)")
    for name, want in expected.items():
        if name not in sd:
            raise ValueError(f"{where}: missing tensor {name!r} (saved from another architecture than {net.arch}?)")
        t = sd[name]
        if not isinstance(t, torch.Tensor):
            raise ValueError(f"{where}: {name!r} is not a tensor, found {type(t).__name__}")
        if t.shape != want.shape:
            raise ValueError(f"{where}: tensor {name!r} has shape {list(t.shape)}, the model expects "
                             f"{list(want.shape)}")
        if t.is_floating_point() and not bool(torch.isfinite(t).all()):
            raise ValueError(f"{where}: tensor {name!r} has non-finite values (NaN or Inf)")
        if name.endswith("running_var") and bool((t < 0).any()):
            raise ValueError(f"{where}: tensor {name!r} has a negative BatchNorm variance "
                             f"({float(t.min()):g})")
        if name.endswith("num_batches_tracked") and bool((t < 0).any()):
            raise ValueError(f"{where}: tensor {name!r} is negative ({int(t.min())})")
        if name == "contact_floor" and not 0 <= float(t) <= MAX_CONTACT_FLOOR:
            raise ValueError(f"{where}: tensor {name!r} is {float(t):g}, expected a value in "
                             f"[0, {MAX_CONTACT_FLOOR:g}] (normalised pressure)")


def weights_digest(net):
    """The digest ptnet records in config.json for model.pt
    (src/model/integrity.cpp): FNV-1a 64 over every parameter, then every
    buffer, in registration order: the name and a NUL, the shape (int64
    each) and the float32 values; a buffer that is not floating point (the
    batch counts), its name and raw bytes. Pure Python: about 85 ns a byte
    (a second for the paper's 14 MB of weights)."""
    h, prime, mask = 0xCBF29CE484222325, 0x100000001B3, (1 << 64) - 1

    def add(data):
        nonlocal h
        for b in data:
            h = ((h ^ b) * prime) & mask

    items = [(n, t, True) for n, t in net.named_parameters()] + [(n, t, False) for n, t in net.named_buffers()]
    for name, t, is_parameter in items:
        add(name.encode() + b"\0")
        t = t.detach().cpu().contiguous()
        if is_parameter or t.is_floating_point():
            t = t.to(torch.float32)
            add(np.asarray(t.shape, dtype="<i8").tobytes())
        add(t.numpy().tobytes())
    return f"{h:016x}"


# ------------------------------------------------------------ around the network

def _body(b):
    """(sex, height_cm, weight_kg) from a tuple or a ptnet.Body; sex 0/1 or female/male."""
    sex, h, w = (b.sex, b.height_cm, b.weight_kg) if hasattr(b, "height_cm") else b
    if isinstance(sex, str):
        sex = {"female": 0, "f": 0, "0": 0, "male": 1, "m": 1, "1": 1}[sex.strip().lower()]
    return int(sex), float(h), float(w)


def attributes(cfg, body, dtype=np.float32):
    """[A] (float32 unless `dtype`): sex, z-scored height, z-scored weight (normalisation of config.json)."""
    n = cfg["normalisation"]
    sex, h, w = _body(body)
    return np.array([1.0 if sex == 1 else 0.0, (h - n["height_mean_cm"]) / n["height_std_cm"],
                     (w - n["weight_mean_kg"]) / n["weight_std_kg"]], dtype=dtype)


def zoom_about_centre(pressure, scale, gain, dtype=np.float32):
    """[T,H,W] (float32 unless `dtype`): each frame zoomed by `scale` about the
    mat centre (bilinear in cell-centre coordinates, outside = 0), times `gain`
    (src/core/zoom.cpp)."""
    x = np.asarray(pressure, dtype=dtype)
    _, rows, cols = x.shape

    def taps(n):
        c = 0.5 * (n - 1)
        pos = c + (np.arange(n) - c) / scale
        i0 = np.floor(pos).astype(np.int64)
        f = pos - i0
        w0 = np.where((i0 >= 0) & (i0 < n), 1 - f, 0).astype(dtype)
        w1 = np.where((i0 + 1 >= 0) & (i0 + 1 < n), f, 0).astype(dtype)
        return np.clip(i0, 0, n - 1), np.clip(i0 + 1, 0, n - 1), w0, w1

    r0, r1, a0, a1 = taps(rows)
    c0, c1, b0, b1 = taps(cols)
    v = np.zeros_like(x)
    for ri, ra in ((r0, a0), (r1, a1)):
        for ci, cb in ((c0, b0), (c1, b1)):
            v += (ra[:, None] * cb[None, :]) * x[:, ri][:, :, ci]
    return x.dtype.type(gain) * v


def window_starts(frames, window, stride):
    """Where Transfer::run's windows start: every `stride` frames (at most the
    window), plus one ending at the last frame."""
    stride = min(stride, window)
    starts = list(range(0, frames - window + 1, stride))
    if starts[-1] != frames - window:
        starts.append(frames - window)
    return starts


def transfer(net, cfg, pressure, source, target, stride=5, raw=False, batch=64):
    """ptnet's whole-sequence transfer (Transfer::run) in PyTorch: float32
    [T >= window, H, W] kPa recorded on `source` -> [T, H, W] kPa for
    `target`; bodies (sex, height_cm, weight_kg) or ptnet.Body."""
    a, n = _arch(cfg), cfg["normalisation"]
    k = a["window"]
    x = np.ascontiguousarray(pressure, dtype=np.float32)
    t = x.shape[0]
    if t < k:
        raise ValueError(f"transfer: sequence has {t} frames, the model's window needs at least {k}")
    if a.get("align", "none") == "zoom":
        (_, sh, sw), (_, th, tw) = _body(source), _body(target)
        s = th / sh
        x = zoom_about_centre(x, s, tw / sw / (s * s))
    starts = window_starts(t, k, stride)
    scale = n["pressure_scale_kpa"]
    m = input_margin(a)                                                       # context frames each side
    inp = with_margin(torch.from_numpy(x) * float(np.float32(1.0 / scale)), m)  # [T+2m,H,W] normalised
    total = torch.zeros(x.shape, dtype=torch.float32)
    cover = torch.zeros(t, dtype=torch.float32)
    sa = torch.from_numpy(attributes(cfg, source)).view(1, ATTRIBUTES)
    ta = torch.from_numpy(attributes(cfg, target)).view(1, ATTRIBUTES)
    with torch.no_grad():
        for b in range(0, len(starts), batch):
            chunk = starts[b:b + batch]
            windows = torch.stack([inp[s:s + k + 2 * m] for s in chunk])       # [n,K+2m,H,W]
            s_n, t_n = sa.expand(len(chunk), ATTRIBUTES), ta.expand(len(chunk), ATTRIBUTES)
            y = net(windows, s_n, t_n)
            if a.get("mirror", False):
                y = 0.5 * (y + net(windows.flip(-1), s_n, t_n).flip(-1))
            for i, s in enumerate(chunk):
                total[s:s + k] += y[i]
                cover[s:s + k] += 1.0
    out = (total / cover.view(t, 1, 1) * scale).numpy()
    threshold = n.get("contact_threshold_kpa", 0)
    if not raw and threshold > 0:
        out[out < threshold] = 0
    return out
