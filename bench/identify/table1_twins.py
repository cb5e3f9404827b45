#!/usr/bin/env python3
"""Table-1-style twins: does the shipped pellet study find generating values that are not the paper's?

For every generating point (NORMK, SHEARK) of a set and every noise seed, this script makes a
synthetic pressure-volume curve with `demfit simulate` (1 % Gaussian noise, the way the shipped
target was made), points a copy of the study file at it, runs `demfit identify`, and prints one row
per twin: runs, the answer's NORMK and SHEARK errors, whether each 95 % interval contains the
generating value, the stop kind and the warnings. A summary line gives the share of twins with
NORMK within 3 % and the interval coverage. Conditions (commit, load average, wall time) are
printed beside the figures.

Two fixed sets of 8 points over the study's box (NORMK 0.01-2, log scale; SHEARK 0.1-0.6), both
with points off the paper's valley (low NORMK with high SHEARK and the reverse): `tune` to choose
the study settings on, `heldout` for the figure reported. Only the Python standard library.

Usage: bench/identify/table1_twins.py [--demfit PATH] [--study FILE] [--set tune|heldout]
           [--seeds 1,2] [--points K] [--particles N] [--jobs 2] [--work DIR]
  --particles N: a coarse variant (pellet.particle_count = N in both the target and the model)
  --points K: only the first K points of the set (a smoke run)
  --resume: continue the studies already in --work (target reused, `demfit identify --resume`):
            stored runs are not repeated, so a newer demfit re-decides the answer, its interval
            checks and its report from the same runs (plus any run the newer rules add)
"""
import argparse
import json
import os
import pathlib
import sqlite3
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
# (NORMK, SHEARK); the paper's generating point is (0.875046, 0.299582).
SETS = {
    "tune": [(0.05, 0.5), (0.12, 0.2), (0.3, 0.45), (0.6, 0.15), (0.875046, 0.299582), (1.2, 0.55), (1.6, 0.25),
             (0.02, 0.35)],
    "heldout": [(0.04, 0.25), (0.09, 0.55), (0.2, 0.3), (0.45, 0.5), (0.7, 0.4), (1.0, 0.12), (1.4, 0.45),
                (1.9, 0.35)],
}
NOISE = 0.01


def load():
    return " ".join(pathlib.Path("/proc/loadavg").read_text().split()[:3])


def run(argv, log):
    with open(log, "w") as out:
        return subprocess.run(argv, stdout=out, stderr=subprocess.STDOUT).returncode


def make_target(args, work, normk, sheark, seed):
    out = work / "target"
    if args.resume and (out / "pressure_volume.csv").exists():
        return out / "pressure_volume.csv"
    sets = ["normk=%r" % normk, "sheark=%r" % sheark, "pellet.max_travel=0.0045"]
    if args.particles:
        sets.append("pellet.particle_count=%d" % args.particles)
    code = run([args.demfit, "simulate", str(ROOT / "cases/pellet_compression.json"), "--out", str(out), "--noise",
                str(NOISE), "--seed", str(seed), "--set", *sets], work / "simulate.log")
    return out / "pressure_volume.csv" if code == 0 else None


def make_study(args, work, target, seed):
    study = json.loads(pathlib.Path(args.study).read_text())
    study["targets"][0]["csv"] = str(target)
    study["seed"] = seed
    if args.particles:
        study["model"].setdefault("overrides", {}).setdefault("pellet", {})["particle_count"] = args.particles
    path = work / "study.json"
    path.write_text(json.dumps(study, indent=1))
    return path


def read_result(out):
    """The study's stored result (runs, stop kind) from study.db."""
    db = sqlite3.connect(str(out / "study.db"))
    try:
        return json.loads(db.execute("SELECT value FROM meta WHERE key='result_json'").fetchone()[0])
    finally:
        db.close()


def read_warnings(out):
    """The warning lines of report.md."""
    marker = "- **warning:** "
    return [line[len(marker):] for line in (out / "report.md").read_text().splitlines() if line.startswith(marker)]


def twin(args, index, normk, sheark, seed):
    work = args.work / ("%s_p%d_s%d" % (args.set, index, seed))
    work.mkdir(parents=True, exist_ok=True)
    target = make_target(args, work, normk, sheark, seed)
    if target is None:
        return "simulate failed: see %s" % (work / "simulate.log"), None
    out = work / "out"
    start = time.time()
    code = run([args.demfit, "identify", str(make_study(args, work, target, seed)), "--jobs", str(args.jobs), "--out",
                str(out)] + (["--resume"] if args.resume else []), work / ("resume.log" if args.resume else "identify.log"))
    wall = time.time() - start
    if code != 0:
        return "identify failed (exit %d): see %s" % (code, work / ("resume.log" if args.resume else "identify.log")), None
    best = json.loads((out / "best_parameters.json").read_text())
    result = read_result(out)
    row = {"runs": result.get("runs"), "wall": wall, "stop": result.get("stop_kind", result.get("stop_reason", "?")),
           "warnings": read_warnings(out)}
    for name, truth in (("normk", normk), ("sheark", sheark)):
        value = best["parameters"][name]
        lower, upper = best["variables"][name]["interval_95"]
        row[name] = (100.0 * (value / truth - 1.0), lower <= truth <= upper)
    return None, row


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--demfit", default=str(ROOT / "build/apps/demfit"))
    parser.add_argument("--study", default=str(ROOT / "cases/table1_study.json"))
    parser.add_argument("--set", choices=sorted(SETS), default="heldout")
    parser.add_argument("--seeds", default="1,2")
    parser.add_argument("--points", type=int, default=0)
    parser.add_argument("--particles", type=int, default=0)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--work", type=pathlib.Path, default=None)
    parser.add_argument("--resume", action="store_true")
    args = parser.parse_args()
    args.work = args.work or pathlib.Path(tempfile.mkdtemp(prefix="table1_twins_"))
    seeds = [int(s) for s in args.seeds.split(",")]
    points = SETS[args.set][: args.points or None]
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    print("table1 twins: set %s, %d points x seeds %s, study %s, %s, noise %.0f %%, --jobs %d, commit %s, work %s; "
          "load %s" % (args.set, len(points), seeds, args.study,
                       "%d particles" % args.particles if args.particles else "the case's particles", 100 * NOISE,
                       args.jobs, commit, args.work, load()), flush=True)
    print("%-8s %-8s %4s %4s %8s %5s %8s %5s %-16s %7s  %s" % ("NORMK", "SHEARK", "seed", "runs", "NORMK err", "in95",
          "SHEARK err", "in95", "stop", "wall s", "warnings"), flush=True)
    rows = []
    for index, (normk, sheark) in enumerate(points):
        for seed in seeds:
            error, row = twin(args, index, normk, sheark, seed)
            if error:
                print("%-8.4g %-8.4g %4d  %s" % (normk, sheark, seed, error), flush=True)
                continue
            rows.append(row)
            print("%-8.4g %-8.4g %4d %4s %+8.2f%% %5s %+8.2f%% %5s %-16s %7.0f  %s  [load %s]" % (
                normk, sheark, seed, row["runs"], row["normk"][0], row["normk"][1], row["sheark"][0],
                row["sheark"][1], str(row["stop"])[:16], row["wall"], len(row["warnings"]), load()), flush=True)
    if not rows:
        sys.exit("table1 twins: no twin finished")
    within = sum(abs(r["normk"][0]) <= 3.0 for r in rows)
    covered = sum(r["normk"][1] for r in rows)
    covered_s = sum(r["sheark"][1] for r in rows)
    print("summary: NORMK within 3 %% on %d of %d twins (%.0f %%); 95 %% intervals contain NORMK on %d, SHEARK on %d "
          "of %d; runs per twin %s; load %s" % (within, len(rows), 100.0 * within / len(rows), covered, covered_s,
                                                 len(rows), sorted(r["runs"] for r in rows), load()))


if __name__ == "__main__":
    main()
