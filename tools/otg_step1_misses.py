"""Classifies the misses of step 1's property test against the Ruckig wheel.

    cargo test --release -p trajkit --test otg_step1_shapes -- --ignored --nocapture 2> misses.txt
    python3 tools/otg_step1_misses.py misses.txt [--jsonl OUT] [--exe target/release/trajkit]

Every miss line of the test (`case N (family): T_trajkit > T_built: InputParameter { .. }`)
is solved with the Ruckig wheel (pinned in otg_sweep.py). Ruckig's final state at its own
duration is measured against trajkit's precision contract (position relative to the motion's
scale, `otg_sweep.position_tolerance`; velocity and acceleration as the sweep's checker), and
each miss is put in one class (`ruckig_error` in units of the tolerances):
  a  trajkit longer than Ruckig × (1 + 1e-9) and Ruckig reaches the target (a real miss),
  b  Ruckig as long or longer,
  c  Ruckig shorter only by missing the target,
  e  Ruckig shorter by at most 1e-5, reaching the target within the tolerance, but trajkit
     given the final position Ruckig actually reached as its target is at most Ruckig's
     duration × (1 + 1e-9): Ruckig stops short of the target (`otg_sweep.by_ruckig_error`,
     the sweep's `longer_by_ruckig_error`),
  f  Ruckig fails.
Prints the counts per class and family, and the class-a cases; `--jsonl OUT` writes every
case with its class, both durations, Ruckig's errors (in units of the tolerance) and the
problem in the sweep's format.
"""
import argparse
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import otg_sweep as sw  # noqa: E402  (sets up the wheel's environment)

ruckig = sw.ruckig
LINE = re.compile(r"^case (\d+) \((\w+)\): (\S+) > (\S+): InputParameter \{(.*)\}\s*$")
FIELDS = ("current_position", "current_velocity", "current_acceleration", "target_position",
          "target_velocity", "target_acceleration", "max_velocity", "max_acceleration", "max_jerk")


def parse(line):
    m = LINE.match(line)
    if not m:
        return None
    body = m.group(5)
    p = {}
    for k in FIELDS:
        v = re.search(r"\b" + k + r": \[([^\]]*)\]", body).group(1)
        p[k] = [float(v)]
    return int(m.group(1)), m.group(2), float(m.group(3)), float(m.group(4)), p


def ruckig_end(p):
    """Ruckig's duration, its final errors in units of trajkit's tolerances and its final
    position (None when it fails)."""
    inp = ruckig.InputParameter(1)
    for k in FIELDS:
        setattr(inp, k, p[k])
    traj = ruckig.Trajectory(1)
    try:
        res = ruckig.Ruckig(1, 0.001).calculate(inp, traj)
    except Exception:
        return None
    if res not in (ruckig.Result.Working, ruckig.Result.Finished):
        return None
    pe, ve, ae = (x[0] for x in traj.at_time(traj.duration))
    p0, pf = p["current_position"][0], p["target_position"][0]
    tol_p = sw.position_tolerance(p0, pf, abs(pe - p0))
    scale_v = max(abs(p["current_velocity"][0]), p["max_velocity"][0])
    err = (abs(pe - pf) / tol_p, abs(ve - p["target_velocity"][0]) / (1e-10 + 1e-13 * scale_v),
           abs(ae - p["target_acceleration"][0]) / 1e-10)
    return traj.duration, err, pe


def classify(tk, rd, p, exe):
    if rd is None:
        return "f"
    tr, err, pe = rd
    if tk <= tr * (1 + 1e-9):
        return "b"
    if max(err) > 1.0:
        return "c"
    return "e" if sw.by_ruckig_error(exe, p, [pe], tr, tk) is not None else "a"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("misses")
    ap.add_argument("--jsonl", default="")
    ap.add_argument("--exe", default=os.path.join(sw.ROOT, "target", "release", "trajkit"))
    ap.add_argument("--no-venv", action="store_true")
    args = ap.parse_args()
    out = open(args.jsonl, "w") if args.jsonl else None
    counts = {}
    for line in open(args.misses):
        c = parse(line)
        if c is None:
            continue
        case, fam, tk, built, p = c
        rd = ruckig_end(p)
        k = classify(tk, rd, p, args.exe)
        counts.setdefault(k, {}).setdefault(fam, 0)
        counts[k][fam] += 1
        rec = {"case": case, "family": fam, "class": k, "trajkit": tk, "built": built,
               "ruckig": rd[0] if rd else None, "ruckig_error": rd[1] if rd else None, "problem": p}
        if k == "a":
            print(json.dumps(rec))
        if out:
            out.write(json.dumps(rec) + "\n")
    for k in sorted(counts):
        print(k, sum(counts[k].values()), counts[k])


if __name__ == "__main__":
    main()
