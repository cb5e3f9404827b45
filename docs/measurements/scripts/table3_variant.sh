#!/bin/bash
# Runs `demfit reproduce table3` on a copy of cases/ whose Table 3 study differs from the shipped
# one only in the study seed and the given edits, for docs/measurements/README.md readings 8, 9, 12, 13 and 16
# (study seeds, friction scale, final selection, budgets, NORMK bound, sampling strategy). The copy lives in WORK/cases with
# WORK/data linked to the repository's data/, because reproduce reads its studies from --data's
# sibling cases/. Prints the report's Surface RMS and How sure lines.
# Usage: table3_variant.sh DEMFIT WORK SEED [frics_log_scale=true|false] [candidates=N] [replicates=N] [iterations=N] [normk_lower=X] [strategy=S] [points=N] [smoothing=X] [cheap=JSON cheap_runs=N] [quick]
#   cheap=JSON: a cheap level whose case overrides are JSON (e.g. '{"drum":{"duration":1.0}}'), with cheap_runs=N runs
#   e.g. table3_variant.sh build/apps/demfit /tmp/t3v/lin2 2 frics_log_scale=false
set -eu
demfit=$1 work=$2 seed=$3
shift 3
source "$(dirname "$0")/copy_cases.sh"
quick=()
study="$work/cases/table3_study.json"
edits=()
for arg in "$@"; do
  case "$arg" in
    quick) quick=(--quick); study="$work/cases/table3_study_quick.json" ;;
    *) edits+=("$arg") ;;
  esac
done
python3 - "$study" "$seed" "${edits[@]}" <<'PY'
import json, sys
path, seed, edits = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
study = json.load(open(path))
study["seed"] = seed
for edit in edits:
    key, value = edit.split("=", 1)
    if key == "frics_log_scale":
        if value not in ("true", "false"):
            sys.exit("table3_variant.sh: frics_log_scale must be true or false, not '%s'" % value)
        next(v for v in study["variables"] if v["name"] == "frics")["log_scale"] = (value == "true")
    elif key == "candidates":
        study["final_selection"]["candidates"] = int(value)
    elif key == "replicates":
        study["final_selection"]["replicates"] = int(value)
    elif key == "iterations":
        study["stopping"]["max_iterations"] = int(value)
    elif key == "normk_lower":
        next(v for v in study["variables"] if v["name"] == "normk")["lower"] = float(value)
    elif key == "strategy":
        study["sampling"]["strategy"] = value
    elif key == "points":
        study["sampling"]["points_per_iteration"] = int(value)
    elif key == "smoothing":
        study.setdefault("surrogate", {})["smoothing"] = float(value)
    elif key == "cheap":
        study.setdefault("cheap_level", {})["overrides"] = json.loads(value)
    elif key == "cheap_runs":
        study.setdefault("cheap_level", {})["runs"] = int(value)
    else:
        sys.exit("table3_variant.sh: unknown edit '%s' (frics_log_scale=, candidates=, replicates=, iterations=, normk_lower=, strategy=, points=, smoothing=, cheap=, cheap_runs=)" % key)
json.dump(study, open(path, "w"), indent=1)
PY
"$demfit" reproduce table3 "${quick[@]}" --jobs 2 --data "$work/data" --out "$work/out" > "$work/log" 2>&1 ||
  { tail -n 3 "$work/log" >&2; exit 1; }
grep -E "^Surface RMS|^How sure|final selection: run" "$work/log"
