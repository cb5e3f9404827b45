#!/bin/bash
# Runs the shipped Table 1 study (cases/table1_study.json) on a copy that differs only in the study
# seed and the given edits, with `demfit identify --jobs 2`, for docs/measurements/README.md readings 10 and 11
# (which point estimate of NORMK is right most often). Prints, from the study store, the answer's
# NORMK (the best run, or the run the study's final_selection names), the posterior median and the
# least-squares centre, each with its error against the generating
# value 0.875046 (SPEC 2.1), and the posterior interval (before and after the interval check when
# the study has one; the check runs after the answer and never moves it).
# Usage: table1_variant.sh DEMFIT WORK SEED [no_interval_check] [strategy=NAME] [points=N] [iterations=N]
#                          [lowest_run]   (lowest_run: no final_selection, the best single run is the answer)
#   e.g. table1_variant.sh build/apps/demfit /tmp/t1v/s2 2 no_interval_check strategy=expected_improvement
set -eu
demfit=$1 work=$2 seed=$3
shift 3
source "$(dirname "$0")/copy_cases.sh"
study="$work/cases/table1_study.json"
python3 - "$study" "$seed" "$@" <<'PY'
import json, sys
path, seed, edits = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
study = json.load(open(path))
study["seed"] = seed
for edit in edits:
    key, _, value = edit.partition("=")
    if edit == "no_interval_check":
        study.pop("interval_check", None)
    elif edit == "lowest_run":
        study.pop("final_selection", None)
    elif key == "strategy":
        study["sampling"]["strategy"] = value
    elif key == "points":
        study["sampling"]["points_per_iteration"] = int(value)
    elif key == "iterations":
        study["stopping"]["max_iterations"] = int(value)
    else:
        sys.exit("table1_variant.sh: unknown edit '%s' (no_interval_check, lowest_run, strategy=, points=, "
                 "iterations=)" % edit)
json.dump(study, open(path, "w"), indent=1)
PY
"$demfit" identify "$study" --jobs 2 --out "$work/out" > "$work/log" 2>&1
python3 - "$work/out/study.db" <<'PY'
import json, sqlite3, sys
truth = 0.875046
db = sqlite3.connect(sys.argv[1])
result = json.loads(db.execute("SELECT value FROM meta WHERE key='result_json'").fetchone()[0])
u = result["uncertainty"]
best = result["best_parameters"]["normk"]
post = u.get("posterior", {}).get("variables", {}).get("normk", {})
lsq = u.get("least_squares_estimate", {}).get("normk")
def err(x):
    return "%+.2f %%" % (100 * (x / truth - 1)) if isinstance(x, (int, float)) else "-"
print("runs %d  answer NORMK %.6g (%s)" % (result["runs"], best, err(best)))
print("posterior median %s (%s)  interval [%s, %s]" % (post.get("median"), err(post.get("median")),
      post.get("sampled_lower_95", post.get("lower_95")), post.get("sampled_upper_95", post.get("upper_95"))))
if "sampled_lower_95" in post:
    print("after the interval check [%s, %s]" % (post["lower_95"], post["upper_95"]))
print("least-squares centre %s (%s)" % (lsq, err(lsq)))
PY
