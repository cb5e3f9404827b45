#!/usr/bin/env python3
"""Does the data prefer the generating point? The objective at a Table-1 twin's truth, replicated.

For each twin of a `table1_twins.py` work folder (WORK/<set>_p<K>_s<seed>), this script copies the
twin's study with every variable boxed to its generating value ± 1e-4 (relative), no interval check,
one iteration and at most 5 runs, and runs `demfit identify` on it: run 0/0 is the generating point
itself, the others differ from it by at most 1e-4 of each value — round-off replicates, since a
pellet run responds chaotically to any change (docs/study_format.md, "round-off replicates"). It
prints their objectives beside the twin study's answer and its replicated objective (from the
twin's report.md), so one can tell a search that stopped short (the truth fits better than the
answer, replicated) from data that cannot tell the two apart (the answer fits as well or better).

Usage: bench/identify/table1_twins_truth.py --work WORK --twins heldout_p5_s1,heldout_p7_s1 [--demfit PATH] [--jobs 2]
Every file goes to WORK/truth_<twin>/. Only the Python standard library.
"""
import argparse
import csv
import json
import pathlib
import re
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from table1_twins import SETS  # noqa: E402  the generating points, one list for both scripts


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--work", required=True)
    p.add_argument("--twins", required=True)
    p.add_argument("--demfit", default=str(ROOT / "build" / "apps" / "demfit"))
    p.add_argument("--jobs", default="2")
    a = p.parse_args()
    work = pathlib.Path(a.work).resolve()
    print("| twin | NORMK, SHEARK | objective at the truth: run 0/0 and 4 replicates | mean | answer's objective (replicated mean) | answer NORMK |")
    print("|---|---|---|---|---|---|")
    for twin in a.twins.split(","):
        m = re.fullmatch(r"(tune|heldout)_p(\d+)_s(\d+)", twin)
        if not m:
            sys.exit("--twins: %s is not <set>_p<K>_s<seed>" % twin)
        truth = SETS[m.group(1)][int(m.group(2))]
        source = work / twin
        study = json.loads((source / "study.json").read_text())
        for variable, value in zip(study["variables"], truth):
            variable.update(lower=value * (1 - 1e-4), upper=value * (1 + 1e-4), initial=value)
        study.pop("interval_check", None)
        study["stopping"] = {"max_iterations": 1, "max_runs": 5}
        study["final_selection"] = {"method": "lowest_run"}
        folder = work / ("truth_" + twin)
        folder.mkdir(exist_ok=True)
        (folder / "study.json").write_text(json.dumps(study, indent=1))
        out = folder / "out"
        argv = [a.demfit, "identify", str(folder / "study.json"), "--out", str(out), "--jobs", a.jobs, "--no-plots"]
        if out.exists():
            argv.append("--resume")
        done = subprocess.run(argv, capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit("failed: %s\n%s" % (" ".join(argv), done.stderr[-2000:]))
        at_truth = [float(r["objective"]) for r in csv.DictReader(open(out / "evaluations.csv")) if r["status"] == "ok"]
        answer = json.loads((source / "out" / "best_parameters.json").read_text())
        report = (source / "out" / "report.md").read_text()
        best = re.search(r"best objective: ([0-9.eE+-]+)", report).group(1)
        replicated = re.search(r"average [0-9.eE+-]+ and ([0-9.eE+-]+)", report)
        answer_text = best + (" (%s)" % replicated.group(1) if replicated else "")
        print("| %s | %g, %g | %s | %.3g | %s | %.4g |" % (twin, truth[0], truth[1], ", ".join("%.3g" % x for x in at_truth),
                                                       statistics.mean(at_truth), answer_text,
                                                       answer["variables"]["normk"]["value"]))


if __name__ == "__main__":
    main()
