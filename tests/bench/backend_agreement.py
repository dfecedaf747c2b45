#!/usr/bin/python3
"""How closely a backend follows golden on the scene family, member by member:

    tests/bench/backend_agreement.py build/bin/evms [--seeds 32] [--split validation] [--backend fixed]
        [--types still,translation,...] [--jobs 2] [--min-ari 0.99] [--evms-args "..."]

Each member is made by `evms gen --family TYPE --seed S` (validation seeds from 1000, tuning
from 1), run by `evms run` on golden and on the backend with the same settings, and the two
events.csv files scored by `evms metrics --chunk-us 10000 --least`, golden's labels as the
truth: the 10 ms chunk of the least ARI is what the issue on the method judges agreement by
(at least 0.99). Prints a line a member, then how many fall below --min-ari; exits with
status 1 when any does.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from multiprocessing import Pool

TYPES = ["still", "translation", "rotation", "zoom", "6dof", "shake", "crossing"]


def member(job):
    evms, backend, evms_args, scratch, scene_type, seed = job
    folder = os.path.join(scratch, "%s%d" % (scene_type, seed))
    subprocess.run([evms, "gen", "--family", scene_type, "--seed", str(seed), "--out", folder], check=True,
                   stdout=subprocess.DEVNULL)
    outs = {}
    for name in ("golden", backend):
        outs[name] = os.path.join(folder, name)
        subprocess.run([evms, "run", os.path.join(folder, "events.txt"), "--quiet", "--backend", name, "--out", outs[name]]
                       + evms_args, check=True, stdout=subprocess.DEVNULL)
    scores = subprocess.run([evms, "metrics", "--chunk-us", "10000", "--least", "--truth",
                             os.path.join(outs["golden"], "events.csv"), "--pred",
                             os.path.join(outs[backend], "events.csv")],
                            check=True, capture_output=True, text=True).stdout
    least = next(line for line in scores.splitlines() if line.startswith("least-chunk "))
    fields = least.split()
    ari, start = float(fields[1]), fields[fields.index("t_us") + 1].rstrip(",")
    shutil.rmtree(folder)
    return scene_type, seed, ari, start


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("evms")
    ap.add_argument("--seeds", type=int, default=32)
    ap.add_argument("--split", choices=["validation", "tuning"], default="validation")
    ap.add_argument("--backend", default="fixed")
    ap.add_argument("--types", default=",".join(TYPES))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--min-ari", type=float, default=0.99)
    ap.add_argument("--evms-args", default="", help="settings for both runs, e.g. \"--motion-split 0\"")
    a = ap.parse_args()
    base = 1000 if a.split == "validation" else 1
    with tempfile.TemporaryDirectory() as scratch:
        jobs = [(a.evms, a.backend, a.evms_args.split(), scratch, t, base + k) for t in a.types.split(",") for k in range(a.seeds)]
        with Pool(a.jobs) as pool:
            results = pool.map(member, jobs)
    below = 0
    for scene_type, seed, ari, start in results:
        mark = "" if ari >= a.min_ari else "   below %g" % a.min_ari
        below += ari < a.min_ari
        print("%-12s %5d  least chunk ARI %.6f from t_us %s%s" % (scene_type, seed, ari, start, mark))
    print("%d of %d members have a 10 ms chunk below ARI %g (%s against golden)" % (below, len(results), a.min_ari, a.backend))
    return 1 if below else 0


if __name__ == "__main__":
    sys.exit(main())
