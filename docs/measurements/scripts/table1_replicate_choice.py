#!/usr/bin/env python3
"""Docs/reproduce.md reading 12, "Would replicates fix seed 10?": from finished Table 1 studies (one
store per seed, answer at the predicted optimum) and the replicated misfits of table1_valley.sh at
each study's two candidate points, prints which point a replicate comparison would answer with.

Usage:
  table1_replicate_choice.py pairs STORE...        one line per store: seed, the verification run's
                                                    NORMK and SHEARK, the lowest loop run's, objectives
  table1_replicate_choice.py choose PAIRS VALLEY    VALLEY holds s{seed}_po.txt and s{seed}_best.txt,
                                                    the outputs of table1_valley.sh with 4 replicates
STORE is a study's out/ folder named .../s{seed}/out (the seed is read from the name)."""
import json, os, re, sqlite3, statistics, sys

TRUTH = 0.875046  # the generating NORMK (SPEC 2.1)


def pairs(stores):
    for store in stores:
        seed = int(re.search(r"s(\d+)/out/?$", store).group(1))
        db = sqlite3.connect(os.path.join(store, "study.db"))
        rows = db.execute("SELECT iteration, point, kind, parameters, objective FROM evaluations "
                          "WHERE kind != 'replicate' AND objective IS NOT NULL").fetchall()
        verification = [r for r in rows if r[2] == "verification"][0]
        loop = [r for r in rows if r[0] <= verification[0]]  # not the interval check's runs
        lowest = min(loop, key=lambda r: r[4])
        v, b = json.loads(verification[3]), json.loads(lowest[3])
        print(seed, repr(v["normk"]), repr(v["sheark"]), repr(b["normk"]), repr(b["sheark"]), verification[4], lowest[4])


def replicated(path):
    """NORMK and the misfits of the one point in a table1_valley.sh output, or None."""
    if not os.path.exists(path):
        return None
    lines = [l for l in open(path) if l.strip() and not l.startswith("NORMK")]
    fields = lines[-1].split()
    return float(fields[0]), [float(x) for x in fields[-4:]]


def choose(pairs_file, valley):
    def err(normk):
        return 100 * (normk / TRUTH - 1)
    rules = {"predicted optimum": [], "lower mean": [], "lower median": []}
    for line in open(pairs_file):
        seed = line.split()[0]
        po = replicated(os.path.join(valley, "s%s_po.txt" % seed))
        if po is None:
            sys.exit("table1_replicate_choice.py: %s has no s%s_po.txt; run table1_valley.sh there first"
                     % (valley, seed))
        best = replicated(os.path.join(valley, "s%s_best.txt" % seed)) or po  # the same point: no choice
        by_mean = po if statistics.mean(po[1]) <= statistics.mean(best[1]) else best
        by_median = po if statistics.median(po[1]) <= statistics.median(best[1]) else best
        print("seed %3s  predicted optimum %+6.2f %%  lowest run %+6.2f %%  by mean %+6.2f %%  by median %+6.2f %%"
              % (seed, err(po[0]), err(best[0]), err(by_mean[0]), err(by_median[0])))
        for rule, point in (("predicted optimum", po), ("lower mean", by_mean), ("lower median", by_median)):
            rules[rule].append(abs(err(point[0])))
    for rule, errors in rules.items():
        print("%-18s within 2 %%: %d of %d, mean |error| %.2f %%, median %.2f %%, largest %.2f %%"
              % (rule, sum(e <= 2 for e in errors), len(errors), statistics.mean(errors), statistics.median(errors),
                 max(errors)))


if __name__ == "__main__":
    if len(sys.argv) >= 3 and sys.argv[1] == "pairs":
        pairs(sys.argv[2:])
    elif len(sys.argv) == 4 and sys.argv[1] == "choose":
        choose(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
