#!/usr/bin/env python3
"""A study store with a cheap level -> OUT/cheap.csv and OUT/fine.csv for bench_rbf_multi_fidelity.

Usage: table3_levels_to_csv.py STUDY.db OUT
Log-scaled variables are written as log10 of their values; the bounds to pass to the benchmark
(VAR:LOWER:UPPER, log10 for those) are printed. Replicates are left out of fine.csv.
"""
import json
import math
import sqlite3
import sys

db, out = sys.argv[1], sys.argv[2]
con = sqlite3.connect(db)
study = json.loads(con.execute("select value from meta where key='study_json'").fetchone()[0])
vs = study["variables"]
names = [v["name"] for v in vs]
def val(v, x): return math.log10(x) if v.get("log_scale") else x
for level, cond in (("cheap", "iteration = -1"), ("fine", "iteration >= 0 and kind != 'replicate'")):
    with open(f"{out}/{level}.csv", "w") as f:
        f.write("iteration,point,kind,status,objective," + ",".join(names) + "\n")
        for it, pt, kind, status, obj, params in con.execute(f"select iteration, point, kind, status, objective, parameters from evaluations where {cond} order by iteration, point"):
            p = json.loads(params)
            f.write(f"{it},{pt},{kind},{status},{obj}," + ",".join(repr(val(v, p[v['name']])) for v in vs) + "\n")
print(" ".join(f"{v['name']}:{val(v, v['lower']) if not (v.get('log_scale')) else math.log10(v['lower'])}:{val(v, v['upper'])}" for v in vs))
