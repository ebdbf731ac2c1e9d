#!/usr/bin/python3
"""scripts/make-gait-trial.py [OUT_DIR]: a synthetic gait-lab trial, markers
and force plates of one physically consistent walk, for the tests that must
run without ../shared (docs/physics.md, "The committed trial").

Writes into OUT_DIR (default tests/data/gait/ beside this script's folder):
  walk.trc         markers, 60 Hz, 2.5 s, 24 markers of the Delaware /
                   gait2354 set, mm, lab axes Y up, X forward, Z right
  walk_static.trc  the standing calibration trial (0.2 s), with the knee
                   and ankle epicondyle / malleolus markers the walk lacks
  walk_grf.mot     two plates (OpenSim storage), 180 Hz: `ground_force_`
                   under the right foot, `1_ground_force_` under the left
  trials.csv       the trials CSV of `ptnet physics-bench`
and prints the figures the trial implies (the naive reference's, the force
low-passed at 4 Hz, the marker path's readings). Deterministic: the same
bytes on every run (no random numbers; numbers printed at fixed precision).

The physics (one subject: male, 1.75 m, 70 kg; an instrumented treadmill
with one belt and plate per foot, belt 1.10 m/s):
 1. Gait events: stride T = 1.10 s (109 steps/min), stance 62 % of the
    stride (0.682 s), so each double support is 12 % of it; the right heel
    strikes at 0.12 s + k T, the left half a stride later.
 2. Each foot's vertical force over its stance (u = 0..1) is the usual two
    humps, a sum of smooth bumps (b(u; p, q) = u^p (1-u)^q scaled to peak
    at 1): A [b(u; 2, 8) + 0.95 b(u; 8, 2)] + M b(u; 4, 4), humps at 20 and
    80 % of stance. A and M are set so that the valley at mid-stance is
    0.75 BW and the mean of the whole-body force F over a stride is m g
    exactly (each stance carries m g T / 2, B-function integrals): peaks
    1.15 and 1.10 BW, 1.30 BW in double support. Fore-aft: braking then
    propulsion, 0.18 BW [b(u; 2, 6) - b(u; 6, 2)] backwards-then-forwards,
    zero net impulse per stance. Medio-lateral: 0.06 of the foot's vertical
    force, towards the midline.
 3. Newton on the whole body: the centre of mass (CoM) accelerates as
    F / m - g (vertical) and F_x / m, F_z / m (horizontal), integrated twice
    on a 3600 Hz grid (trapezoids, the mean removed once per integral, so
    the CoM's path is periodic: the mean of F over a stride is m g). The
    CoM travels at 1.10 m/s plus that oscillation, overground.
 4. The feet: flat on the floor through mid-stance; a heel rocker from heel
    strike (foot pitched 20 degrees toes up, turning about the heel, landed
    at rest) to foot flat at 13 % of stance (minimum-jerk); a forefoot
    rocker from heel off at 50 % of stance to toe off (40 degrees heel up,
    quadratic, turning about the sole under the metatarsal heads, the toes
    flat); between, the foot swings: cubic Hermite curves in the heel's
    position and the foot's pitch that leave with the rocker's velocities
    and land at rest, plus a lift of 0.10 m x 16 s^2 (1-s)^2, so every
    trajectory is smooth to the velocity. A foot does not slide while it
    is loaded. Feet straight ahead, under the hip joints. The hip passes
    over the flat foot's ankle at the fraction of stance that lets the
    pelvis stand highest (a golden-section search: 0.365).
 5. The skeleton is ptnet's canonical one for 1.75 m (Drillis-Contini:
    thigh 0.245 H, shank 0.246 H, hips 0.0475 H either side of the pelvis,
    ankle 0.039 H above the sole, the toe joint 0.0790 H ahead and 0.030 H
    below it; the trunk upright, arms hanging). The knees follow from the
    hips and the ankles (two-bone chains bent forwards). Masses: de Leva
    (1996), male, with de Leva's centre-of-mass fractions along the thigh
    (0.4095), shank (0.4459) and foot (0.4415, heel to toe tip); the head,
    trunk and arms move with the pelvis. The pelvis is placed so that this
    body's CoM follows step 3 exactly (fixed-point iteration on the legs'
    share), its mean height the highest at which no knee straightens beyond
    the chain's reach (0.999 of thigh + shank at the longest).
 6. Markers on that skeleton, placed so that the methods of docs/markers.md
    recover its joints: ASIS and V.Sacral by Harrington et al. (2007)
    inverted (inter-ASIS width 0.33 PW + 7.3 mm = the hips' lateral offset,
    depth 0.155 m); three-marker thigh and shank clusters, rigid on their
    segments; epicondyles and malleoli (static trial only) either side of
    the joint centres; heel (30 mm above the sole, 10 mm behind the heel),
    the 1st and 5th metatarsal heads (their midpoint 10 mm above the toe
    joint, normal to the heel -> toe line); sternum; acromia (0.17 x the
    biacromial breadth above the shoulder joints, Rab et al. 2002).
 7. The treadmill: every lab position is the overground one less the belt's
    1.10 m/s x t (the subject stays over the plates, a planted foot moves
    back with the belt); the forces are the overground ones (a constant
    velocity changes no acceleration). The centre of pressure runs along
    the foot from the heel (0.06 of the foot's length from its back) to the
    toes (0.92), knots at foot flat (0.22), heel off (0.62) and 80 % of
    stance (0.76), on the plate's surface (Y = 0); no free torque.
Not modelled: the segments' own angular momentum (the CoP is prescribed, not
derived from the moments), pelvis rotation and list, arm swing, knee and
ankle motion outside the sagittal plane.
"""
import math
import os
import sys

import numpy as np

# ------------------------------------------------------------------ subject
H = 1.75            # stature, m
MASS = 70.0         # kg
G = 9.81            # m/s^2 (ptnet's anthropometry::kGravity)
BW = MASS * G

# ------------------------------------------------------------------ gait
FPS = 60            # marker frames per second
PLATE_HZ = 180      # plate samples per second (3 per frame: no sample on a frame's edge)
GRID_HZ = 3600      # integration grid (a multiple of both)
FRAMES = 151        # 2.5 s
STATIC_FRAMES = 12
STRIDE = 1.10       # s
STANCE = 0.62       # of the stride
SPEED = 1.10        # m/s, the belt
RIGHT_STRIKE = 0.12  # s, first right heel strike
HUMP = (2, 8)       # the humps u^2 (1-u)^8 and u^8 (1-u)^2: peaks at 20 and 80 % of stance
PEAK_2 = 0.95       # second hump / first
VALLEY = 0.75       # BW, the force at mid-stance
AP_BW = 0.18        # fore-aft bumps' peak, BW
ML_RATIO = 0.06     # medio-lateral force / vertical force
U_FLAT, U_HEEL_OFF = 0.13, 0.50
PITCH_STRIKE, PITCH_OFF = math.radians(20), math.radians(-40)
LIFT = 0.10         # m, the swing's lift (the peak of 16 s^2 (1-s)^2)
COP_KNOTS = ([0.0, U_FLAT, U_HEEL_OFF, 0.80, 1.0], [0.06, 0.22, 0.62, 0.76, 0.92])
REACH = 0.999       # longest hip-ankle distance / (thigh + shank)
LAB_X = 0.50        # m, the pelvis' mean fore-aft place on the treadmill

N_STRIDE = round(STRIDE * GRID_HZ)          # 2640 grid samples a stride
N_STANCE = STANCE * N_STRIDE                # 1636.8
T_STANCE = STANCE * STRIDE
T_SWING = STRIDE - T_STANCE
STEP = round(GRID_HZ / FPS)                 # grid samples per frame
PSTEP = round(GRID_HZ / PLATE_HZ)           # grid samples per plate sample
OFFSET = {"R": round(RIGHT_STRIKE * GRID_HZ), "L": round(RIGHT_STRIKE * GRID_HZ) + N_STRIDE // 2}

# ------------------------------------------------------------------ skeleton (canonical, fractions of H)
THIGH, SHANK = 0.245 * H, 0.246 * H
HIP_HALF = 0.0475 * H
ANKLE_UP = 0.039 * H
HEEL_BACK = 0.0334 * H       # heel back behind the ankle
MTP_FWD, MTP_UP = 0.0790 * H + HEEL_BACK, 0.009 * H   # toe joint from the heel back, above the sole
FOOT_LEN = 0.152 * H
TOE_LEN = FOOT_LEN - MTP_FWD
SHOULDER_HALF = 0.5 * 0.259 * H
SHOULDER_UP = (0.818 - 0.530) * H   # pelvis -> shoulder joints
CHEST_UP = (0.720 - 0.530) * H
# de Leva (1996), male: mass percent and CoM fraction from the proximal end.
PCT = {"thigh": 14.16, "shank": 4.33, "foot": 1.37}
COM_FRAC = {"thigh": 0.4095, "shank": 0.4459, "foot": 0.4415}
PCT_RIGID = 100 - 2 * sum(PCT.values())     # head, trunk, arms: 60.28

# Markers on the pelvis (Harrington inverted) and the segments.
PW = (HIP_HALF - 0.0073) / 0.33           # inter-ASIS width
PD = 0.155                                # ASIS midpoint -> sacral marker
ASIS_FWD = 0.24 * PD + 0.0099             # hip centres behind the ASIS midpoint
ASIS_UP = 0.30 * PW + 0.0109              # and below it
KNEE_HALF, ANKLE_HALF = 0.0275 * H, 0.0195 * H
ACROMION_UP = 0.17 * 2 * SHOULDER_HALF
# Clusters: (fraction down the segment, forward, outward) in metres.
THIGH_SET = {"Upper": (0.30, 0.0, 0.085), "Front": (0.55, 0.075, 0.030), "Rear": (0.70, -0.055, 0.070)}
SHANK_SET = {"Upper": (0.25, 0.0, 0.060), "Front": (0.50, 0.050, 0.025), "Rear": (0.70, -0.045, 0.050)}
HEEL_MARKER = (-0.010, 0.030)             # (forward of the heel back, above the sole)
MT_HALF = 0.035                           # 1st / 5th metatarsal heads either side of the foot's line


def toe_reference():
    """The metatarsal markers' midpoint (foot frame) that is 10 mm above the
    toe joint normal to the heel marker -> midpoint line (docs/markers.md)."""
    t = np.array([MTP_FWD, MTP_UP + 0.010])
    for _ in range(50):
        d = t - np.array(HEEL_MARKER)
        n = np.array([-d[1], d[0]]) / np.hypot(*d)
        t = np.array([MTP_FWD, MTP_UP]) + 0.010 * n
    return t


TOE_REF = toe_reference()


# ------------------------------------------------------------------ forces
def bump(u, p, q):
    """u^p (1-u)^q scaled to peak 1, zero outside [0, 1]."""
    u = np.clip(u, 0.0, 1.0)
    peak = (p / (p + q)) ** p * (q / (p + q)) ** q
    return u ** p * (1 - u) ** q / peak


def beta(p, q):
    return math.gamma(p + 1) * math.gamma(q + 1) / math.gamma(p + q + 2)


# Each stance carries m g T / 2 (the stride's mean force is m g), and the
# valley at mid-stance is VALLEY: the scales A of the humps and M of the middle bump.
def _vertical_scales():
    b = lambda p, q: beta(p, q) / ((p / (p + q)) ** p * (q / (p + q)) ** q)  # a bump's mean over stance
    mid = bump(np.array([0.5]), *HUMP)[0] * (1 + PEAK_2)                     # the humps at u = 0.5
    mean = BW * STRIDE / 2 / T_STANCE
    hump_mean = b(*HUMP) + PEAK_2 * b(*HUMP[::-1])
    a = (mean - VALLEY * BW * b(4, 4)) / (hump_mean - mid * b(4, 4))
    return a, VALLEY * BW - a * mid


A_VERT, M_VERT = _vertical_scales()


def stance_phase(k, side):
    """(stride index, u in stance or None) at grid sample k (integer array)."""
    rel = k - OFFSET[side]
    n = np.floor_divide(rel, N_STRIDE)
    phi = rel - n * N_STRIDE
    return n, phi / N_STANCE


def foot_forces(k, side):
    """Vertical, fore-aft, lateral (+ left) force of one foot (N) at grid samples k."""
    _, u = stance_phase(k, side)
    on = u < 1.0
    fz = np.where(on, A_VERT * (bump(u, *HUMP) + PEAK_2 * bump(u, *HUMP[::-1])) + M_VERT * bump(u, 4, 4), 0.0)
    fx = np.where(on, -AP_BW * BW * (bump(u, 2, 6) - bump(u, 6, 2)), 0.0)
    fy = ML_RATIO * fz * (1.0 if side == "R" else -1.0)  # towards the midline
    return fz, fx, fy


def periodic_double_integral(a):
    """Position of a periodic acceleration a (grid samples of one stride):
    trapezoids, the mean removed from the velocity and from the position."""
    dt = 1.0 / GRID_HZ
    a = a - a.mean()
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[:-1] + a[1:]) * dt)])
    v -= v.mean()
    x = np.concatenate([[0.0], np.cumsum(0.5 * (v[:-1] + v[1:]) * dt)])
    return x - x.mean()


def com_oscillation():
    """The CoM's oscillation about its mean path over one stride [N_STRIDE, 3]
    (forward, left, up), from the whole body's ground reaction."""
    k = np.arange(N_STRIDE)
    f = [foot_forces(k, s) for s in "RL"]
    fz = f[0][0] + f[1][0]
    fx = f[0][1] + f[1][1]
    fy = f[0][2] + f[1][2]
    return np.stack([periodic_double_integral(fx / MASS), periodic_double_integral(fy / MASS),
                     periodic_double_integral(fz / MASS - G)], axis=1)


# ------------------------------------------------------------------ feet
def smooth(s):
    """Minimum-jerk 0 -> 1: zero velocity and acceleration at both ends."""
    s = np.clip(s, 0.0, 1.0)
    return s ** 3 * (10 - 15 * s + 6 * s * s)


def rotate(a, b, pitch):
    """Foot-frame (forward, up) vector turned by pitch (toes up positive)."""
    c, s = np.cos(pitch), np.sin(pitch)
    return a * c - b * s, a * s + b * c


# The fraction of stance at which the hip passes over the flat foot's ankle
# (the pelvis travels at SPEED): chosen by main() where the legs let the
# pelvis stand highest.
OVER_ANKLE = [0.5]


def strike_x(n, side):
    """Heel back's forward place at the heel strike of stride n (overground)."""
    first = SPEED * (RIGHT_STRIKE + OVER_ANKLE[0] * T_STANCE) - HEEL_BACK
    return first + (0.0 if side == "R" else 0.5 * SPEED * STRIDE) + n * SPEED * STRIDE


def stance_foot(n, u, side):
    """Heel back (x, z) and pitch in stance."""
    # The heel rocker lands the foot at rest; the forefoot rocker turns ever
    # faster to toe off (quadratic), and the swing goes on from there.
    pitch = np.where(u < U_FLAT, PITCH_STRIKE * (1 - smooth(u / U_FLAT)),
                     np.where(u > U_HEEL_OFF, PITCH_OFF * ((u - U_HEEL_OFF) / (1 - U_HEEL_OFF)) ** 2, 0.0))
    x0 = strike_x(n, side)
    # Heel rocker and flat: about the heel back; forefoot rocker: about the sole under the toe joint.
    dx, dz = rotate(-MTP_FWD, 0.0, pitch)
    fore = u > U_HEEL_OFF
    return np.where(fore, x0 + MTP_FWD + dx, x0), np.where(fore, dz, 0.0), pitch


def hermite(tau, p0, v0, p1, v1):
    """Cubic Hermite from p0 (rate v0 per unit tau) to p1 (rate v1)."""
    t2, t3 = tau * tau, tau * tau * tau
    return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + tau) * v0 + (3 * t2 - 2 * t3) * p1 + (t3 - t2) * v1


def foot_state(k, side):
    """Heel back (x, z), pitch of one foot at grid samples k (overground)."""
    n, u = stance_phase(k, side)
    xs, zs, ps = stance_foot(n, np.minimum(u, 1.0), side)
    # Swing, from toe off of stride n to the strike of stride n + 1: cubic
    # Hermite curves that leave with the stance's last velocities (per unit
    # tau: d/du x (swing / stance duration)) and land at rest, plus the lift.
    tau = np.clip((u * N_STANCE - N_STANCE) / (N_STRIDE - N_STANCE), 0.0, 1.0)
    end, before = stance_foot(n, 1.0, side), stance_foot(n, 1.0 - 1e-6, side)
    rate = [(a - b) / 1e-6 * (T_SWING / T_STANCE) for a, b in zip(end, before)]
    xw = hermite(tau, end[0], rate[0], strike_x(n + 1, side), 0.0)
    zw = hermite(tau, end[1], rate[1], 0.0, 0.0) + LIFT * 16 * tau ** 2 * (1 - tau) ** 2
    pw = hermite(tau, end[2], rate[2], PITCH_STRIKE, 0.0)
    swing = u >= 1.0
    return np.where(swing, xw, xs), np.where(swing, zw, zs), np.where(swing, pw, ps)


def foot_point(state, a, b):
    """World (x, z) of the foot-frame point (a forward of the heel back, b above the sole)."""
    x, z, pitch = state
    dx, dz = rotate(a, b, pitch)
    return x + dx, z + dz


# ------------------------------------------------------------------ the body
def legs(pelvis, k):
    """Hip, knee, ankle, toe joints and heel back / toe tip of each foot
    [T, 3] (world: x forward, y left, z up), for pelvis [T, 3] at samples k."""
    out = {}
    for side, lat in (("R", -1.0), ("L", 1.0)):
        state = foot_state(k, side)
        hip = pelvis + np.array([0.0, lat * HIP_HALF, 0.0])
        y = np.full(len(k), lat * HIP_HALF)
        ax, az = foot_point(state, HEEL_BACK, ANKLE_UP)
        ankle = np.stack([ax, y, az], axis=1)
        tx, tz = foot_point(state, MTP_FWD, MTP_UP)
        hx, hz = foot_point(state, 0.0, 0.0)
        ex, ez = foot_point(state, FOOT_LEN, 0.0)
        d = ankle - hip
        dist = np.linalg.norm(d, axis=1)
        e = d / dist[:, None]
        along = (dist ** 2 + THIGH ** 2 - SHANK ** 2) / (2 * dist)
        off = np.sqrt(np.maximum(0.0, THIGH ** 2 - along ** 2))
        fwd = np.array([1.0, 0.0, 0.0]) - e[:, [0]] * e  # forward, normal to hip -> ankle
        fwd /= np.linalg.norm(fwd, axis=1)[:, None]
        out[side] = {"hip": hip, "knee": hip + along[:, None] * e + off[:, None] * fwd, "ankle": ankle,
                     "toe": np.stack([tx, y, tz], axis=1), "heel": np.stack([hx, y, hz], axis=1),
                     "tip": np.stack([ex, y, ez], axis=1), "reach": dist / (THIGH + SHANK), "state": state}
    return out


def limb_com(lg):
    """The legs' share of the CoM, relative to the pelvis [T, 3] (mass-weighted / total)."""
    s = 0.0
    for side in "RL":
        j = lg[side]
        s = s + PCT["thigh"] * (j["hip"] + COM_FRAC["thigh"] * (j["knee"] - j["hip"]))
        s = s + PCT["shank"] * (j["knee"] + COM_FRAC["shank"] * (j["ankle"] - j["knee"]))
        s = s + PCT["foot"] * (j["heel"] + COM_FRAC["foot"] * (j["tip"] - j["heel"]))
    return s / 100.0


def pelvis_path(k, osc, height, strict=False):
    """The pelvis at samples k such that the body's CoM is `height` + the
    oscillation (and SPEED forward): the rigid part moves with the pelvis,
    the legs' share is taken off by fixed-point iteration (to 1e-12 m;
    `strict`: or fail; the searches also try heights the legs cannot reach)."""
    target = osc[np.mod(k, N_STRIDE)] + np.stack([SPEED * k / GRID_HZ, 0 * k, height + 0 * k], axis=1)
    pelvis = target.copy()
    for _ in range(60):
        lg = legs(pelvis, k)
        # CoM = (PCT_RIGID pelvis + legs) / 100 (the rigid part's own offset is a constant)
        com = PCT_RIGID / 100.0 * pelvis + limb_com(lg)
        new = pelvis + (target - com)
        if np.max(np.abs(new - pelvis)) < 1e-12:
            break
        pelvis = new
    else:
        if strict:
            raise SystemExit("make-gait-trial: the pelvis did not converge")
    return pelvis, legs(pelvis, k)


def highest_pelvis(k, osc):
    """The CoM's mean level at which the longest hip-ankle reach is REACH."""
    lo, hi = 0.6, 1.1
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        _, lg = pelvis_path(k, osc, mid)
        reach = max(lg[s]["reach"].max() for s in "RL")
        lo, hi = (mid, hi) if reach < REACH else (lo, mid)
    return lo


# ------------------------------------------------------------------ markers
def segment_markers(top, bottom, lat, spec, prefix):
    """Cluster markers rigid on the segment top -> bottom (lat: outward unit)."""
    axis = bottom - top
    length = np.linalg.norm(axis, axis=1)[:, None]
    down = axis / length
    out_ = lat - np.sum(lat * down, axis=1)[:, None] * down
    out_ /= np.linalg.norm(out_, axis=1)[:, None]
    fwd = np.cross(out_, down) if lat[0, 1] < 0 else np.cross(down, out_)
    return {prefix + name: top + f * axis + a * fwd + o * out_ for name, (f, a, o) in spec.items()}


def body_markers(pelvis, lg, static):
    """Every marker (world, m) [T, 3], by Delaware name."""
    T = len(pelvis)
    m = {}
    hip_mid = pelvis
    origin = hip_mid + np.array([ASIS_FWD, 0.0, ASIS_UP])
    m["R.ASIS"] = origin + np.array([0.0, -0.5 * PW, 0.0])
    m["L.ASIS"] = origin + np.array([0.0, 0.5 * PW, 0.0])
    m["V.Sacral"] = origin - np.array([PD, 0.0, 0.0])
    for side, lat_y in (("R", -1.0), ("L", 1.0)):
        j = lg[side]
        lat = np.tile([0.0, lat_y, 0.0], (T, 1))
        m.update(segment_markers(j["hip"], j["knee"], lat, THIGH_SET, side + ".Thigh."))
        m.update(segment_markers(j["knee"], j["ankle"], lat, SHANK_SET, side + ".Shank."))
        if static:
            for name, centre, half in (("Knee", j["knee"], KNEE_HALF), ("Ankle", j["ankle"], ANKLE_HALF)):
                m[side + "." + name + ".Lat"] = centre + half * lat
                m[side + "." + name + ".Med"] = centre - half * lat
        state = j["state"]
        y = j["ankle"][:, 1]
        hx, hz = foot_point(state, *HEEL_MARKER)
        m[side + ".Heel"] = np.stack([hx, y, hz], axis=1)
        tx, tz = foot_point(state, *TOE_REF)
        m[side + ".Toe.Lat"] = np.stack([tx, y + lat_y * MT_HALF, tz], axis=1)
        m[side + ".Toe.Med"] = np.stack([tx, y - lat_y * MT_HALF, tz], axis=1)
        m[side + ".Acromium"] = pelvis + np.array([0.0, lat_y * SHOULDER_HALF, SHOULDER_UP + ACROMION_UP])
    m["Sternum"] = pelvis + np.array([0.09, 0.0, CHEST_UP])
    return m


ORDER = ["R.ASIS", "L.ASIS", "V.Sacral",
         "R.Thigh.Upper", "R.Thigh.Front", "R.Thigh.Rear", "L.Thigh.Upper", "L.Thigh.Front", "L.Thigh.Rear",
         "R.Shank.Upper", "R.Shank.Front", "R.Shank.Rear", "L.Shank.Upper", "L.Shank.Front", "L.Shank.Rear",
         "R.Heel", "R.Toe.Lat", "R.Toe.Med", "L.Heel", "L.Toe.Lat", "L.Toe.Med",
         "Sternum", "R.Acromium", "L.Acromium"]
STATIC_EXTRA = ["R.Knee.Lat", "R.Knee.Med", "L.Knee.Lat", "L.Knee.Med",
                "R.Ankle.Lat", "R.Ankle.Med", "L.Ankle.Lat", "L.Ankle.Med"]


def to_lab(p, t, belt=SPEED):
    """World (x forward, y left, z up) overground -> the treadmill's lab
    (X forward, Y up, Z right), m: the belt carries a planted foot back."""
    return np.stack([p[:, 0] - belt * t + LAB_X, p[:, 2], -p[:, 1]], axis=1)


def num(v, decimals):
    """v at fixed precision, never '-0.00'."""
    s = "%.*f" % (decimals, v)
    return s[1:] if s.startswith("-") and not s.strip("-0.") else s


def trc_text(name, markers, order, t, belt):
    frames = len(t)
    lines = ["PathFileType\t4\t(X/Y/Z)\t" + name,
             "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames",
             "%.2f\t%.2f\t%d\t%d\tmm\t%.2f\t1\t%d" % (FPS, FPS, frames, len(order), FPS, frames),
             "Frame#\tTime\t" + "\t".join(n + "\t\t" for n in order),
             "\t\t" + "\t".join("X%d\tY%d\tZ%d" % (i + 1, i + 1, i + 1) for i in range(len(order))),
             ""]
    lab = {n: 1000.0 * to_lab(markers[n], t, belt) for n in order}
    for f in range(frames):
        cells = ["%d" % (f + 1), num(t[f], 6)]
        for n in order:
            cells += [num(v, 2) for v in lab[n][f]]
        lines.append("\t".join(cells))
    return "\n".join(lines) + "\n"


def cop_u(u):
    return np.interp(u, *COP_KNOTS)


def plates_text(k):
    """The plates' storage file at grid samples k: right foot first."""
    t = k / GRID_HZ
    cols, names = [t], ["time"]
    for prefix, side in (("ground_force_", "R"), ("1_ground_force_", "L")):
        fz, fx, fy = foot_forces(k, side)
        _, u = stance_phase(k, side)
        state = foot_state(k, side)
        on = (u < 1.0) & (fz > 0)
        cx, cz = foot_point(state, cop_u(np.minimum(u, 1.0)) * FOOT_LEN, 0.0)
        lat = -HIP_HALF if side == "R" else HIP_HALF
        cop = to_lab(np.stack([cx, np.full(len(k), lat), 0 * cx], axis=1), t)
        cols += [fx, fz, -fy, np.where(on, cop[:, 0], 0.0), 0 * t, np.where(on, cop[:, 2], 0.0)]
        names += [prefix + c for c in ("vx", "vy", "vz", "px", "py", "pz")]
    rows = ["walk_grf.mot", "version=1", "nRows=%d" % len(k), "nColumns=%d" % len(names), "inDegrees=yes",
            "endheader", "\t".join(names)]
    decimals = [6] + [2, 2, 2, 5, 5, 5] * 2
    for i in range(len(k)):
        rows.append("\t".join(num(c[i], d) for d, c in zip(decimals, cols)))
    return "\n".join(rows) + "\n"


def gaussian_lowpass(x, hz, fps):
    """x low-passed by a Gaussian of -3 dB at hz (ends held), as documented
    for ptnet's load (docs/physics.md): the limit of a 4 Hz estimate."""
    sigma = math.sqrt(math.log(2.0)) / (2 * math.pi * hz) * fps
    r = int(math.ceil(4 * sigma))
    w = np.exp(-0.5 * (np.arange(-r, r + 1) / sigma) ** 2)
    w /= w.sum()
    padded = np.concatenate([np.full(r, x[0]), x, np.full(r, x[-1])])
    return np.convolve(padded, w, mode="valid")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "tests", "data", "gait")
    os.makedirs(out_dir, exist_ok=True)
    osc = com_oscillation()
    k = np.arange(FRAMES) * STEP
    # Golden-section search of the hip-over-ankle phase for the highest pelvis.
    a, b = 0.3, 0.7
    r = (math.sqrt(5) - 1) / 2
    for _ in range(20):
        c, d = b - r * (b - a), a + r * (b - a)
        OVER_ANKLE[0] = c
        hc = highest_pelvis(k, osc)
        OVER_ANKLE[0] = d
        hd = highest_pelvis(k, osc)
        a, b = (a, d) if hc > hd else (c, b)
    OVER_ANKLE[0] = round(0.5 * (a + b), 4)
    height = highest_pelvis(k, osc)
    t = k / GRID_HZ
    pelvis, lg = pelvis_path(k, osc, height, strict=True)
    walk = body_markers(pelvis, lg, static=False)

    # The static trial: standing, feet flat under the hips, knees straight.
    ts = np.arange(STATIC_FRAMES) / FPS
    stand = np.tile([HEEL_BACK, 0.0, ANKLE_UP + THIGH + SHANK], (STATIC_FRAMES, 1))
    slg = {}
    for side, lat in (("R", -1.0), ("L", 1.0)):
        state = (np.zeros(STATIC_FRAMES), np.zeros(STATIC_FRAMES), np.zeros(STATIC_FRAMES))
        hip = stand + np.array([0.0, lat * HIP_HALF, 0.0])
        ankle = hip - np.array([0.0, 0.0, THIGH + SHANK])
        slg[side] = {"hip": hip, "knee": hip - np.array([0.0, 0.0, THIGH]), "ankle": ankle, "state": state}
    static = body_markers(stand, slg, static=True)
    files = {
        "walk.trc": trc_text("walk.trc", walk, ORDER, t, SPEED),
        "walk_static.trc": trc_text("walk_static.trc", static, ORDER + STATIC_EXTRA, ts, 0.0),
        "walk_grf.mot": plates_text(np.arange(0, (FRAMES - 1) * STEP + 1, PSTEP)),
        "trials.csv": "trial,markers,static,plates,sex,height_cm,weight_kg,coverage\n"
                      "walk,walk.trc,walk_static.trc,walk_grf.mot,male,%.1f,%.1f,all\n" % (H * 100, MASS),
    }
    for name, text in files.items():
        with open(os.path.join(out_dir, name), "w", newline="\n") as f:
            f.write(text)
    report(k, t, pelvis, lg, walk, height, osc, out_dir, files)


def report(k, t, pelvis, lg, walk, height, osc, out_dir, files):
    """What the trial implies, for the tests and docs/physics.md."""
    kk = np.arange(0, (FRAMES - 1) * STEP + 1)
    fz = sum(foot_forces(kk, s)[0] for s in "RL")
    # The plates as the bench reads them: each frame the mean of its 3 samples.
    ps = np.arange(0, (FRAMES - 1) * STEP + 1, PSTEP)
    fzp = sum(foot_forces(ps, s)[0] for s in "RL") / BW
    box = np.array([fzp[max(0, 3 * i - 1):3 * i + 2].mean() for i in range(FRAMES)])
    naive = np.sqrt(np.mean((box - 1.0) ** 2))
    # The force a 4 Hz estimate of the CoM's acceleration sees: m (g + lowpass(z'')).
    com_z = height + osc[np.mod(k, N_STRIDE), 2]
    acc = np.zeros(FRAMES)
    acc[1:-1] = (com_z[2:] - 2 * com_z[1:-1] + com_z[:-2]) * FPS * FPS
    acc[0], acc[-1] = acc[1], acc[-2]
    lp = 1 + gaussian_lowpass(acc, 4.0, FPS) / G
    lp_rmse = np.sqrt(np.mean((lp - box) ** 2))
    knee = []
    for s in "RL":
        j = lg[s]
        a, b = j["hip"] - j["knee"], j["ankle"] - j["knee"]
        cos = np.sum(a * b, axis=1) / np.linalg.norm(a, axis=1) / np.linalg.norm(b, axis=1)
        knee.append(180 - np.degrees(np.arccos(np.clip(cos, -1, 1))))
    loading = np.concatenate([kn[(stance_phase(k, s)[1] > 0.1) & (stance_phase(k, s)[1] < 0.5)] for kn, s in zip(knee, "RL")])
    knee = np.concatenate(knee)
    hips = 0.5 * (lg["R"]["hip"][:, 2] + lg["L"]["hip"][:, 2])
    low = np.min([walk[n][:, 2] for n in ("R.Heel", "R.Toe.Lat", "R.Toe.Med", "L.Heel", "L.Toe.Lat", "L.Toe.Med")],
                 axis=0)
    floor = np.partition(low, len(low) // 20)[len(low) // 20] - 0.030
    stature = (np.partition(hips, len(hips) // 2)[len(hips) // 2] - floor) / 0.530
    single = [f for f in range(FRAMES)
              if (stance_phase(np.array([k[f]]), "R")[1][0] < 1) != (stance_phase(np.array([k[f]]), "L")[1][0] < 1)]
    print("make-gait-trial: wrote %s (%s)" % (out_dir, ", ".join("%s %d B" % (n, len(v)) for n, v in files.items())))
    one = foot_forces(np.arange(OFFSET["R"], OFFSET["R"] + int(N_STANCE)), "R")[0] / BW
    half = len(one) // 2
    print("  vertical force per foot: peaks %.3f / %.3f BW, valley %.3f BW; total %.3f..%.3f BW"
          % (one[:half].max(), one[half:].max(), one[half], fz.min() / BW, fz.max() / BW))
    print("  CoM path: vertical range %.1f mm, fore-aft %.1f mm, lateral %.1f mm"
          % (1000 * np.ptp(osc[:, 2]), 1000 * np.ptp(osc[:, 0]), 1000 * np.ptp(osc[:, 1])))
    print("  knee flexion %.1f..%.1f deg (10-50 %% of stance: %.1f..%.1f); hip-ankle reach up to %.4f; hip over the ankle at %.4f of stance"
          % (knee.min(), knee.max(), loading.min(), loading.max(), max(lg[s]["reach"].max() for s in "RL"), OVER_ANKLE[0]))
    print("  frames %d, single stance %d; naive reference RMSE %.4f BW; 4 Hz low-passed CoM force RMSE %.4f BW"
          % (FRAMES, len(single), naive, lp_rmse))
    print("  marker path: stature estimate %.4f m (docs/markers.md), pelvis mean height %.4f m, belt %.3f m/s"
          % (stature, pelvis[:, 2].mean(), SPEED))


if __name__ == "__main__":
    main()
