#!/usr/bin/env python3
"""The two Python steps of scripts/lopo.sh (leave one performer out); the
standard library only.

  lopo.py folds CLIPS BODIES WORK
      WORK/bodies_retargeted.csv and WORK/bodies_original.csv (BODIES split
      by role), and one folder a performer P (the subject column of CLIPS),
      WORK/performer_P/ with train_clips.csv (every clip of the other
      performers, take 1) and test_clips.csv (P's clips, take 2); file paths
      made absolute. Prints one line a fold: P, training clips, test clips.
      Files already there must be identical (a resumed run of the same split).
  lopo.py aggregate WORK
      Reads every fold's report/metrics.json (the take-2 average of ptnet
      evaluate: model, body_scale, floor, and its warning about a model no
      better than a baseline) and times.txt, prints the table (and a line a
      warning) and writes WORK/lopo.json.

Errors are one line on stderr naming the file, exit status 1.
"""

import csv
import io
import json
import os
import signal
import sys

# The issue 27 targets: mean RMSE ratio to body scale, mean binary R^2, worst ratio.
kTargetMeanRatio = 0.70  # mean over performers of model RMSE / body-scale RMSE
kTargetBinaryR2 = 0.85  # mean over performers of the model's binary R^2
kTargetWorstRatio = 0.85  # no performer above this ratio


class LopoError(Exception):
    """The one error type: a message naming the file."""


def read_csv(path, required):
    """Rows of a CSV as dicts (RFC 4180, UTF-8 with or without a BOM) and its header."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            reader = csv.DictReader(f)
            header = reader.fieldnames or []
            rows = list(reader)
    except OSError as e:
        raise LopoError(f"{path}: cannot read ({e.strerror})")
    except (csv.Error, UnicodeDecodeError) as e:
        raise LopoError(f"{path}: not a CSV file ({e})")
    missing = [c for c in required if c not in header]
    if missing:
        raise LopoError(f"{path}: expected columns {','.join(required)}, missing {','.join(missing)}")
    for i, row in enumerate(rows, start=2):
        if None in row or any(row[c] is None for c in header):
            raise LopoError(f"{path}:{i}: expected {len(header)} fields")
    return header, rows


def csv_text(header, rows):
    out = io.StringIO()
    w = csv.DictWriter(out, fieldnames=header, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    return out.getvalue()


def write_atomic(path, text):
    """Write text to path through a temporary file in the same folder."""
    tmp = path + ".tmp"
    try:
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(text)
        os.replace(tmp, path)
    except OSError as e:
        raise LopoError(f"{path}: cannot write ({e.strerror})")


def write_once(path, text):
    """Write text, or check that a file already there holds exactly it."""
    if os.path.exists(path):
        with open(path, encoding="utf-8", newline="") as f:
            if f.read() != text:
                raise LopoError(f"{path}: differs from the split of this corpus and bodies; use a new work folder")
        return
    write_atomic(path, text)


def subject_key(s):
    return (0, int(s), s) if s.isdigit() else (1, 0, s)


def folds(clips_path, bodies_path, work):
    header, clips = read_csv(clips_path, ["file", "subject", "category", "take"])
    if not clips:
        raise LopoError(f"{clips_path}: no clips")
    base = os.path.dirname(os.path.abspath(clips_path))
    for c in clips:
        c["file"] = os.path.normpath(os.path.join(base, c["file"]))
    subjects = sorted({c["subject"] for c in clips}, key=subject_key)
    if len(subjects) < 2:
        raise LopoError(f"{clips_path}: leave one performer out needs >= 2 subjects, found {len(subjects)}")

    b_header, bodies = read_csv(bodies_path, ["id", "role"])
    by_role = {r: [b for b in bodies if b["role"] == r] for r in ("retargeted", "original")}
    if len(by_role["retargeted"]) < 2 or len(by_role["original"]) < 2:
        raise LopoError(f"{bodies_path}: expected >= 2 retargeted and >= 2 original bodies, found "
                        f"{len(by_role['retargeted'])} and {len(by_role['original'])}")
    os.makedirs(work, exist_ok=True)
    for role, rows in by_role.items():
        write_once(os.path.join(work, f"bodies_{role}.csv"), csv_text(b_header, rows))

    for s in subjects:
        train = [dict(c, take="1") for c in clips if c["subject"] != s]
        test = [dict(c, take="2") for c in clips if c["subject"] == s]
        fold = os.path.join(work, f"performer_{s}")
        os.makedirs(fold, exist_ok=True)
        write_once(os.path.join(fold, "train_clips.csv"), csv_text(header, train))
        write_once(os.path.join(fold, "test_clips.csv"), csv_text(header, test))
        print(s, len(train), len(test))


def read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise LopoError(f"{path}: cannot read ({e.strerror})")
    except ValueError as e:
        raise LopoError(f"{path}: not JSON ({e})")


def read_settings(path):
    """key=value lines written by lopo.sh."""
    settings = {}
    try:
        with open(path, encoding="utf-8") as f:
            for n, line in enumerate(f, start=1):
                line = line.rstrip("\n")
                if not line:
                    continue
                if "=" not in line:
                    raise LopoError(f"{path}:{n}: expected key=value, found {line!r}")
                k, v = line.split("=", 1)
                settings[k] = v
    except OSError as e:
        raise LopoError(f"{path}: cannot read ({e.strerror})")
    return settings


def read_times(path):
    """NAME=SECONDS lines of a fold's times.txt; a step resumed once has two, summed."""
    times = {}
    try:
        with open(path, encoding="utf-8") as f:
            for n, line in enumerate(f, start=1):
                k, sep, v = line.strip().partition("=")
                try:
                    if not sep:
                        raise ValueError
                    times[k] = times.get(k, 0.0) + float(v)
                except ValueError:
                    raise LopoError(f"{path}:{n}: expected NAME=SECONDS, found {line.strip()!r}")
    except OSError as e:
        raise LopoError(f"{path}: cannot read ({e.strerror})")
    return times


def validation_ratio(path):
    """The model's validation RMSE / body scale's on the same windows (the
    training performers' retargeted bodies), from its config.json; None if absent."""
    if not os.path.exists(path):
        return None
    metrics = read_json(path).get("metrics", {})
    try:
        return float(metrics["val_rmse_kpa"]) / float(metrics["val_rmse_zoom_kpa"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        raise LopoError(f"{path}: expected metrics.val_rmse_kpa and metrics.val_rmse_zoom_kpa > 0")


def fold_result(work, subject):
    fold = os.path.join(work, f"performer_{subject}")
    path = os.path.join(fold, "report", "metrics.json")
    m = read_json(path)
    groups = m.get("groups", {})
    if "seen" in groups:
        raise LopoError(f"{path}: holds take-1 (seen) pairs: not a test set of lopo.sh")
    try:
        avg = groups["unseen"]["average"]
        model, scale = avg["model"], avg["body_scale"]
        pairs = int(model["rows"])
        r = {
            "performer": subject,
            "pairs": pairs,
            "rmse_model_kpa": float(model["rmse_kpa"]),
            "rmse_body_scale_kpa": float(scale["rmse_kpa"]),
            "binary_r2_model": float(model["binary_r2"]),
            "binary_r2_body_scale": float(scale["binary_r2"]),
        }
        floor = avg.get("floor")
        r["rmse_floor_kpa"] = float(floor["rmse_kpa"]) if floor else None
        r["binary_r2_floor"] = float(floor["binary_r2"]) if floor else None
    except (KeyError, TypeError, ValueError) as e:
        raise LopoError(f"{path}: expected groups.unseen.average.model and .body_scale with rmse_kpa, "
                        f"binary_r2 and rows ({e!r} missing or not a number)")
    if r["rmse_body_scale_kpa"] <= 0:
        raise LopoError(f"{path}: body_scale rmse_kpa {r['rmse_body_scale_kpa']} is not > 0")
    r["ratio"] = r["rmse_model_kpa"] / r["rmse_body_scale_kpa"]
    _, test = read_csv(os.path.join(fold, "test_clips.csv"), ["file", "subject"])
    _, train = read_csv(os.path.join(fold, "train_clips.csv"), ["file", "subject"])
    r["val_ratio"] = validation_ratio(os.path.join(fold, "model", "config.json"))
    # ptnet evaluate's word on a model no better than the all-zero or copy baseline on validation.
    r["warning"] = m.get("warning")
    r["clips"] = len(test)
    r["train_clips"] = len(train)
    times_path = os.path.join(fold, "times.txt")
    r["wall_s"] = read_times(times_path) if os.path.exists(times_path) else {}
    return r


def mean(xs):
    return sum(xs) / len(xs) if xs else None


def weighted(rows, key):
    n = sum(r["pairs"] for r in rows)
    if any(r[key] is None for r in rows) or n == 0:
        return None
    return sum(r[key] * r["pairs"] for r in rows) / n


def summarise(rows):
    keys = ["rmse_model_kpa", "rmse_body_scale_kpa", "ratio", "binary_r2_model", "binary_r2_body_scale",
            "rmse_floor_kpa", "binary_r2_floor", "val_ratio"]
    by_performer = {k: (None if any(r[k] is None for r in rows) else mean([r[k] for r in rows])) for k in keys}
    by_performer.update(clips=sum(r["clips"] for r in rows), pairs=sum(r["pairs"] for r in rows))
    by_pair = {k: weighted(rows, k) for k in keys if k not in ("ratio", "val_ratio")}
    by_pair["ratio"] = by_pair["rmse_model_kpa"] / by_pair["rmse_body_scale_kpa"]
    by_pair.update(clips=by_performer["clips"], pairs=by_performer["pairs"])
    return by_performer, by_pair


def fmt(x, digits):
    return "n/a" if x is None else f"{x:.{digits}f}"


def table(rows, by_performer, by_pair):
    lines = ["| performer | clips | pairs | RMSE model (kPa) | RMSE body scale | x body scale | "
             "bin. R^2 model | bin. R^2 body scale | RMSE floor | val. x body scale |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]

    def line(name, r):
        return (f"| {name} | {r['clips']} | {r['pairs']} | {fmt(r['rmse_model_kpa'], 2)} | "
                f"{fmt(r['rmse_body_scale_kpa'], 2)} | {fmt(r['ratio'], 2)} | {fmt(r['binary_r2_model'], 3)} | "
                f"{fmt(r['binary_r2_body_scale'], 3)} | {fmt(r['rmse_floor_kpa'], 3)} | "
                f"{fmt(r.get('val_ratio'), 2)} |")

    lines += [line(r["performer"], r) for r in rows]
    lines.append(line("**mean over performers**", by_performer))
    lines.append(line("mean over pairs", by_pair))
    return "\n".join(lines)


def aggregate(work):
    settings_path = os.path.join(work, "settings.txt")
    settings = read_settings(settings_path) if os.path.exists(settings_path) else {}
    subjects = sorted((d[len("performer_"):] for d in os.listdir(work)
                       if d.startswith("performer_") and os.path.isdir(os.path.join(work, d))), key=subject_key)
    if not subjects:
        raise LopoError(f"{work}: no performer_* folders (run scripts/lopo.sh first)")
    done = [s for s in subjects if os.path.exists(os.path.join(work, f"performer_{s}", "report", "metrics.json"))]
    missing = [s for s in subjects if s not in done]
    if not done:
        raise LopoError(f"{work}: no fold has a report yet")
    rows = [fold_result(work, s) for s in done]
    by_performer, by_pair = summarise(rows)
    worst = max(rows, key=lambda r: r["ratio"])
    targets = {
        "mean_ratio": {"target": f"<= {kTargetMeanRatio}", "value": by_performer["ratio"],
                       "met": by_performer["ratio"] <= kTargetMeanRatio},
        "mean_binary_r2": {"target": f">= {kTargetBinaryR2}", "value": by_performer["binary_r2_model"],
                           "met": by_performer["binary_r2_model"] >= kTargetBinaryR2},
        "worst_ratio": {"target": f"<= {kTargetWorstRatio}", "value": worst["ratio"],
                        "performer": worst["performer"], "met": worst["ratio"] <= kTargetWorstRatio},
    }
    result = {
        "what": "leave one performer out: train on the other performers' clips (take 1, retargeted bodies), "
                "test on the performer's clips (take 2, original bodies); RMSE and binary R^2 are the means "
                "over a performer's pairs (ptnet evaluate's unseen average); ratio = model RMSE / body-scale RMSE; "
                "val_ratio = the same ratio on the training run's validation windows (the other performers)",
        "settings": settings,
        "complete": not missing,
        "missing_performers": missing,
        "performers": rows,
        "mean_over_performers": by_performer,
        "mean_over_pairs": by_pair,
        "targets_issue_27": targets,
    }
    write_atomic(os.path.join(work, "lopo.json"), json.dumps(result, indent=2) + "\n")

    preset = settings.get("preset", "?")
    print(f"leave one performer out, preset {preset}, training seed {settings.get('seed', '?')}: "
          f"{len(done)} of {len(subjects)} folds" + (f" (missing: {', '.join(missing)})" if missing else ""))
    print(table(rows, by_performer, by_pair))
    for r in rows:
        if r["warning"]:
            print(f"warning: performer {r['performer']}: the model's {r['warning']}")
    print(f"targets (issue 27): mean x body scale {by_performer['ratio']:.2f} (<= {kTargetMeanRatio}: "
          f"{'met' if targets['mean_ratio']['met'] else 'not met'}), mean binary R^2 "
          f"{by_performer['binary_r2_model']:.3f} (>= {kTargetBinaryR2}: "
          f"{'met' if targets['mean_binary_r2']['met'] else 'not met'}), worst performer {worst['performer']} "
          f"{worst['ratio']:.2f} x (<= {kTargetWorstRatio}: {'met' if targets['worst_ratio']['met'] else 'not met'})")
    print(f"wrote {os.path.join(work, 'lopo.json')}")


def main(argv):
    usage = "usage: lopo.py folds CLIPS BODIES WORK | lopo.py aggregate WORK"
    if len(argv) >= 2 and argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0
    try:
        if len(argv) == 5 and argv[1] == "folds":
            folds(argv[2], argv[3], argv[4])
        elif len(argv) == 3 and argv[1] == "aggregate":
            aggregate(argv[2])
        else:
            print(usage, file=sys.stderr)
            return 2
    except LopoError as e:
        print(f"lopo: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `| head` ends the output quietly
    sys.exit(main(sys.argv))
