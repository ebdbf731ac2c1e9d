"""How far may a float32 evaluation of a ptnet network be from the exact one?

ptnet (LibTorch; BatchNorm and FiLM folded into the convolutions, channels-last
kernels, ConvTranspose2d run as Conv2d) and ptnet_torch (PyTorch modules) are
two float32 evaluations of one function, summing in orders that depend on the
kernels the CPU gets; neither is the reference. The reference is the network
evaluated in float64 (its own rounding, ~1e-16, is ignored), and each float32
evaluation must lie within a per-cell tolerance of it. The tolerance is
carried through the network beside the float64 values, in two parts:

1. Rounding, `s` (probabilistic rounding error analysis: Higham and Mary,
   SIAM J. Sci. Comput. 41(5), 2019). Every float32 operation rounds its
   exact result r to r (1 + d), |d| <= u = 2^-24, the d independent and of
   mean zero (round to nearest). A dot product of n terms w_i x_i (a
   convolution output: fan-in C_in x 3 x 3 plus the bias; a linear layer:
   in_features + 1), summed in any order, with or without FMA, makes at most
   n + SLACK roundings (SLACK: the eval-mode BatchNorm, the FiLM modulation,
   their folding into the weights, the scale), each of size <= u sum |w||x|,
   so its error is a sum of independent terms whose bounds c_i satisfy
   sum c_i^2 <= (n + SLACK) (u sum |w||x|)^2. An error already in the inputs
   passes through the layer linearly (to first order): sum c_i^2 grows by
   W^2 * s_in^2. ReLU and max do not increase an error. Carried as
   s = sqrt(sum c_i^2) per cell, Hoeffding's inequality gives
   P(|error| >= LAMBDA s) <= 2 exp(-LAMBDA^2 / 2): with LAMBDA = 8, 2.5e-14
   per cell, below 1e-7 for every cell of every comparison of the test suite.
   (The worst-case bound, gamma(n) sum |w||x| carried with |W|, is ~1e-2
   normalised after nine layers here: true, and too loose to test anything.)
2. Discontinuities, `f` (worst case, carried with |W|): where no rounding
   bound exists and the value itself is at stake.
   * Max pooling whose indices max_unpool2d reuses (faithful, skip, residual).
     Where another cell of a 2 x 2 block comes within tolerance of the
     block's maximum, an evaluation may pick it, and the decoder then writes
     its value there instead: every candidate cell of the block may differ by
     the decoded value plus its tolerance. Exact float64 ties are not
     candidates: equal non-zero float64 values come from cells with the same
     receptive field (empty regions of the mat: the bias alone), which every
     evaluation computes alike; equal zeros from a ReLU whose input is below
     minus its tolerance are exact in every evaluation.
   * The contact head (frame network with contact): a logit within tolerance
     of 0 may keep or zero the cell.
   * The contact threshold: an output within tolerance of
     normalisation.contact_threshold_kpa may be kept or zeroed.

The inputs: the zoom alignment (four bilinear taps, float32 weights, the gain)
and the normalisation (x float32(1 / scale)) make at most 12 roundings of
size <= u x (the zoom of |x|); the attributes (float64 rounded to float32) one
of size u |a|.

transfer_bound() evaluates a whole transfer (ptnet_torch.transfer, i.e.
Transfer::run) this way: the float64 output and the tolerance, both in kPa;
check_within() asserts a float32 output lies within it.
"""
import copy
import math

import numpy as np
import torch
import torch.nn.functional as F

import ptnet_torch as pt

U = 2.0 ** -24  # float32 unit roundoff
SLACK = 16      # roundings of a term beyond its dot product (BatchNorm, FiLM, folding, the scale)
LAMBDA = 8.0    # rounding tolerance = LAMBDA s: P(exceeded) <= 2 exp(-32) = 2.5e-14 per cell


class Bounded:
    """A float64 tensor `v`; a float32 evaluation lies within LAMBDA s + f of it."""

    def __init__(self, v, s, f):
        self.v, self.s, self.f = v, s, f

    def tol(self):
        return LAMBDA * self.s + self.f

    def map(self, fn):
        """An operation that moves or copies cells (view, cat, flip, upsampling): all three alike."""
        return Bounded(fn(self.v), fn(self.s), fn(self.f))


def exact(v, roundings=0):
    """An input made by `roundings` roundings of size <= u |v|."""
    return Bounded(v, math.sqrt(roundings) * U * v.abs(), torch.zeros_like(v))


def _cat(parts):
    return Bounded(*(torch.cat([getattr(p, a) for p in parts], 1) for a in "vsf"))


def _relu(pre):
    """ReLU; an input below minus its tolerance gives an exact 0 in every evaluation."""
    live = (pre.v + pre.tol() > 0).double()
    return Bounded(torch.relu(pre.v), pre.s * live, pre.f * live)


def _add(a, b):
    v = a.v + b.v
    size = a.v.abs() + b.v.abs() + a.f + b.f
    return Bounded(v, torch.sqrt(a.s ** 2 + b.s ** 2 + (U * size) ** 2), a.f + b.f)


def _channels(c, like):
    """A per-channel [C] tensor shaped to broadcast over `like` ([N, C, ...] or [N, C])."""
    return c.view(1, -1, *([1] * (like.dim() - 2)))


def _affine(x, layer, fn, fan_in, norm=None):
    """`layer` (float64 Conv2d, ConvTranspose2d or Linear; fn(input, weight,
    bias) its functional form), then the eval-mode BatchNorm `norm`."""
    w = layer.weight
    b = torch.zeros(w.shape[1] if isinstance(layer, torch.nn.ConvTranspose2d) else w.shape[0], dtype=w.dtype)
    if layer.bias is not None:
        b = layer.bias
    v = fn(x.v, w, layer.bias)
    size = fn(x.v.abs() + x.f, w.abs(), None) + _channels(b.abs(), v)           # sum |w||x|
    var_in = fn(x.s ** 2, w ** 2, None)                                          # W^2 * s_in^2
    f = fn(x.f, w.abs(), None)                                                   # |W| * f_in
    if norm is not None:
        v = norm(v)
        scale = 1 / torch.sqrt(norm.running_var + norm.eps)
        beta = torch.zeros_like(scale)
        if norm.weight is not None:
            scale, beta = scale * norm.weight, norm.bias
        scale, beta, mean = (_channels(t.abs(), v) for t in (scale, beta, norm.running_mean))
        size, var_in, f = size * scale + mean * scale + beta, var_in * scale ** 2, f * scale
    return Bounded(v, torch.sqrt(var_in + (fan_in + SLACK) * (U * size) ** 2), f)


def _conv(x, layer, norm=None):
    if isinstance(layer, torch.nn.ConvTranspose2d):  # weight [C_in, C_out, 3, 3]
        fn = lambda t, w, b: F.conv_transpose2d(t, w, b, padding=layer.padding)
        fan_in = layer.weight.shape[0] * 9 + 1
    else:                                            # weight [C_out, C_in, k, k]
        fn = lambda t, w, b: F.conv2d(t, w, b, padding=layer.padding)
        fan_in = layer.weight[0].numel() + 1
    return _affine(x, layer, fn, fan_in, norm)


def _linear(x, layer):
    return _affine(x, layer, F.linear, layer.weight.shape[1] + 1)


def _block_max(t):
    return F.max_pool2d(t, 2, 2, ceil_mode=True)


def _on_cells(t, like):
    """Each 2 x 2 block's value on its cells ([N,C,h,w] -> like's [N,C,H,W])."""
    return t.repeat_interleave(2, 2).repeat_interleave(2, 3)[:, :, :like.shape[2], :like.shape[3]]


def _pool(x):
    """Max pooling (frame network): the maximum moves no more than its inputs."""
    return Bounded(_block_max(x.v), _block_max(x.s), _block_max(x.f))


def _pool_indices(x):
    """Max pooling whose indices the decoder reuses: (pooled Bounded, what _unpool needs)."""
    p, idx = F.max_pool2d(x.v, 2, 2, ceil_mode=True, return_indices=True)
    tol = x.tol()
    tol_max = tol.flatten(2).gather(2, idx.flatten(2)).view_as(p)             # the maximum's tolerance
    reach = x.v + tol >= _on_cells(p - tol_max, x.v)                            # may reach the maximum
    tied = (x.v == _on_cells(p, x.v)) & ((x.v != 0) | (tol == 0))               # alike in every evaluation
    is_max = torch.zeros_like(x.v).flatten(2).scatter_(2, idx.flatten(2), 1.0).view_as(x.v) > 0
    candidate = (reach & ~tied & ~is_max).double()
    doubt = _block_max(candidate) > 0                                           # another cell may win
    anywhere = torch.maximum(candidate, is_max.double()) * _on_cells(doubt.double(), x.v)
    pooled = Bounded(p, _block_max(x.s), _block_max(x.f))
    return pooled, (idx, anywhere, x.v.shape[2:])


def _unpool(d, pooling):
    idx, anywhere, size = pooling
    up = lambda t: F.max_unpool2d(t, idx, 2, 2, output_size=size)
    out = d.map(up)
    moved = anywhere * _on_cells(d.v.abs() + d.tol(), anywhere)                 # the value may land on any candidate
    return Bounded(out.v, out.s, torch.maximum(out.f, moved))


def _keep_where_positive(keep, value):
    """value where keep > 0, else 0: a keep within tolerance of 0 may go either way."""
    sure = (keep.v.abs() > keep.tol()).double()
    on = (keep.v > 0).double()
    return Bounded(value.v * on, value.s * on * sure, value.f * on * sure + (value.v.abs() + value.tol()) * (1 - sure))


def _window_net(net, x, source, target):
    """PressureTransferNet.forward for faithful, skip and residual."""
    skips = net.arch in ("skip", "residual")
    s = [pt.pooled_size(net.rows, net.cols, k) for k in range(pt.POOL_LEVELS + 1)]
    e1 = _relu(_conv(x, net.conv1, net.bn1))
    p1, i1 = _pool_indices(e1)
    e2 = _relu(_conv(p1, net.conv2, net.bn2))
    p2, i2 = _pool_indices(e2)
    e3 = _relu(_conv(p2, net.conv3, net.bn3))
    p3, i3 = _pool_indices(e3)
    h = _relu(_linear(p3.map(lambda t: t.flatten(1)), net.fc_features))
    z = _linear(_cat([h, source]), net.fc_latent)
    d = _relu(_linear(_cat([z, target]), net.fc_decode))
    d = _unpool(d.map(lambda t: t.view(t.shape[0], net.channels[2], *s[3])), i3)
    if skips:
        d = _cat([d, e3])
    d = _unpool(_relu(_conv(d, net.deconv3, net.dbn3)), i2)
    if skips:
        d = _cat([d, e2])
    d = _unpool(_relu(_conv(d, net.deconv2, net.dbn2)), i1)
    if skips:
        d = _cat([d, e1])
    out = _conv(d, net.deconv1)
    if net.arch == "residual":
        out = _add(out, x)
    return _relu(out)


def _frame_net(net, x, source, target):
    """PressureTransferNet.forward for the frame network."""
    f = net.frame
    c = net.context
    n, t, h, w = x.v.shape[0], x.v.shape[1] - 2 * c, x.v.shape[2], x.v.shape[3]  # x holds T + 2 context frames
    film = _linear(_relu(_linear(_cat([source, target]).map(lambda v: v.repeat_interleave(t, 0)), f.film1)), f.film2)

    def block(i, inp):  # relu(norm(conv(x)) (1 + gamma) + beta)
        y = _conv(inp, getattr(f, f"conv{i}"), getattr(f, f"norm{i}"))
        wd, o = f.widths[i], f.offsets[i]
        g = film.map(lambda c: c[:, o:o + wd, None, None])
        g.v = 1 + g.v
        beta = film.map(lambda c: c[:, o + wd:o + 2 * wd, None, None])
        size = g.v.abs() * (y.v.abs() + y.f) + beta.v.abs()
        s = torch.sqrt((g.v * y.s) ** 2 + ((y.v.abs() + y.f) * g.s) ** 2 + beta.s ** 2 + SLACK * (U * size) ** 2)
        return _relu(Bounded(y.v * g.v + beta.v, s, g.v.abs() * y.f + (y.v.abs() + y.f) * g.f + beta.f))

    up = lambda b, like: b.map(lambda c: F.interpolate(c, size=like.v.shape[2:], mode="nearest"))
    e0 = block(0, x.map(lambda v: pt.frames_with_context(v, c)))
    e1 = block(1, _pool(e0))
    e2 = block(2, _pool(e1))
    m = block(3, e2)
    d1 = block(4, _add(_conv(up(m, e1), f.lateral1), e1))
    d0 = block(5, _add(_conv(up(d1, e0), f.lateral0), e0))
    out = _conv(d0, f.head)
    shape = (n, t, h, w)
    pressure = _add(x.map(lambda v: v[:, c:c + t]), out.map(lambda v: v[:, 0].reshape(shape)))
    if not net.contact:
        return _relu(pressure)
    p = _relu(pressure)
    p = Bounded(torch.clamp_min(p.v, float(net.contact_floor)), p.s, p.f)
    return _keep_where_positive(out.map(lambda v: v[:, 1].reshape(shape)), p)


def network_bound(net64, x, source, target):
    """The float64 network on windows x ([N,T,H,W], normalised) and attributes
    ([N,A]), all Bounded: its output [N,T,H,W] (normalised), Bounded."""
    y = (_frame_net if net64.arch == "frame" else _window_net)(net64, x, source, target)
    assert torch.equal(y.v, net64(x.v, source.v, target.v)), "error_bound is out of step with ptnet_torch"
    return y


def _mean(a, b):
    v = 0.5 * (a.v + b.v)
    return Bounded(v, torch.sqrt(0.25 * (a.s ** 2 + b.s ** 2) + 2 * (U * (v.abs() + a.f + b.f)) ** 2),
                   0.5 * (a.f + b.f))


def transfer_bound(net, cfg, pressure, source, target, stride=5, raw=False):
    """ptnet_torch.transfer (Transfer::run) in float64 with the tolerance of a
    float32 evaluation: (output, tolerance), float64 [T, H, W] kPa each."""
    a, n = pt._arch(cfg), cfg["normalisation"]
    net64 = copy.deepcopy(net).double().eval()
    k, scale = a["window"], n["pressure_scale_kpa"]
    x = np.asarray(pressure, dtype=np.float64)
    size = np.abs(x)
    if a.get("align", "none") == "zoom":
        (_, sh, sw), (_, th, tw) = pt._body(source), pt._body(target)
        s = th / sh
        gain = tw / sw / (s * s)
        x, size = (pt.zoom_about_centre(y, s, gain, dtype=np.float64) for y in (x, size))
    t = x.shape[0]
    starts = pt.window_starts(t, k, stride)
    m = pt.input_margin(a)  # each window's input holds m context frames at each end
    stack = lambda y: torch.stack([pt.with_margin(torch.from_numpy(y / scale), m)[i:i + k + 2 * m]
                                   for i in starts])  # [N,K+2m,H,W]
    windows = Bounded(stack(x), math.sqrt(12) * U * stack(size),
                      torch.zeros(len(starts), k + 2 * m, *x.shape[1:]).double())

    def attributes(body):
        v = torch.from_numpy(pt.attributes(cfg, body, dtype=np.float64)).view(1, pt.ATTRIBUTES)
        return exact(v.expand(len(starts), -1).contiguous(), roundings=1)

    sa, ta = attributes(source), attributes(target)
    with torch.no_grad():
        y = network_bound(net64, windows, sa, ta)
        if a.get("mirror", False):
            y = _mean(y, network_bound(net64, windows.map(lambda c: c.flip(-1)), sa, ta).map(lambda c: c.flip(-1)))
    # Each frame: the sum of the `cover` windows covering it, divided by cover, times the scale.
    total, var, f, size = (torch.zeros(x.shape, dtype=torch.float64) for _ in range(4))
    cover = torch.zeros(t, dtype=torch.float64)
    for i, s in enumerate(starts):
        total[s:s + k] += y.v[i]
        var[s:s + k] += y.s[i] ** 2
        f[s:s + k] += y.f[i]
        size[s:s + k] += y.v[i].abs() + y.f[i]
        cover[s:s + k] += 1
    c = cover.view(t, 1, 1)
    out = (total / c * scale).numpy()
    s = (torch.sqrt(var + (c + 3) * (U * size) ** 2) / c * scale).numpy()
    tol = LAMBDA * s + (f / c * scale).numpy()
    threshold = n.get("contact_threshold_kpa", 0)
    if not raw and threshold > 0:
        unsure = np.abs(out - threshold) <= tol
        tol = np.where(unsure, np.abs(out) + tol, np.where(out < threshold, 0.0, tol))
        out = np.where(out < threshold, 0.0, out)
    return out, tol


def check_within(test, name, got, ref, tol, scale):
    """Asserts |got - ref| <= tol cell by cell (kPa); the message names the
    worst cell, in kPa and normalised (/ scale)."""
    excess = np.abs(np.asarray(got, np.float64) - ref) - tol
    worst = np.unravel_index(int(np.argmax(excess)), excess.shape)
    test.assertLessEqual(excess[worst], 0.0,
                         f"{name}: cell {tuple(int(i) for i in worst)}: {got[worst]} kPa, float64 {ref[worst]}, "
                         f"tolerance {tol[worst]} kPa ({tol[worst] / scale:.3g} normalised)")
