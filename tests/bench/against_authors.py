#!/usr/bin/python3
"""evms beside the authors' own clustering (../shared/peer, the mean-shift core of
fbarranco/dvs_clustering_tracking taken out of ROS), on the same scenes, in one run:

    tests/bench/against_authors.py build/bin/evms [--seeds 4] [--repeat 3]

For each scene, the authors' program (with its swapped clamp fixed, `--fix-clamp 1`), `evms run
--preset paper` and `evms run` with the defaults read the same events.txt and write one label per
event. The table gives each one's F (10 ms chunks, noise as singletons, `evms metrics`) and its
wall clock as a whole process (reading, clustering, writing; the median of --repeat runs).

The scenes are 240x180, as the authors' code was written for: members of the scene family's
validation split pinned to 7 shapes and 0.1 Hz of background activity a pixel (about 5 % noise),
and the paper's three shapes-poster scenes. Then the real recordings of ../shared/data/real
that the authors' program can take (it reads events.txt: each recording is converted first, and
evms reads the recording itself), timed only, as they carry no labels. The authors' program is
built here from ../shared/peer with g++ and Debian's libopencv-core-dev; when that folder is
absent the comparison is skipped, saying so.
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

TYPES = ["translation", "rotation", "6dof", "crossing"]
PAPER = ["translation", "rotation", "6dof"]
REAL = ["dvxplorer_indoor.aedat4"]


def build_peer(peer_dir, work):
    source = os.path.join(peer_dir, "authors_clustering.cpp")
    binary = os.path.join(work, "authors_clustering")
    if not os.path.isdir("/usr/include/opencv4"):
        sys.exit("against_authors: the authors' code needs OpenCV's core: apt-get install libopencv-core-dev")
    cmd = ["g++", "-O3", "-march=native", "-std=c++17", "-I/usr/include/opencv4", source, "-o", binary, "-lopencv_core"]
    subprocess.run(cmd, check=True)
    return binary


def timed(cmd, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def f_measure(evms, truth, pred):
    out = subprocess.run([evms, "metrics", "--truth", truth, "--pred", pred, "--chunk-us", "10000"],
                         check=True, capture_output=True, text=True).stdout.split()
    return float(out[4])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("evms")
    ap.add_argument("--seeds", type=int, default=4, help="family members of each type")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each program a scene, for the median time")
    ap.add_argument("--peer", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../../shared/peer"))
    ap.add_argument("--duration-s", type=float, default=1.0, help="length of the family's members")
    ap.add_argument("--keep", help="keep the scenes and outputs in this folder")
    a = ap.parse_args()
    if not os.path.isfile(os.path.join(a.peer, "authors_clustering.cpp")):
        print(f"against_authors: skipped: {os.path.normpath(a.peer)} holds no authors_clustering.cpp")
        return
    evms = os.path.abspath(a.evms)
    work = a.keep or tempfile.mkdtemp(prefix="evms_authors_")
    os.makedirs(work, exist_ok=True)
    peer = build_peer(a.peer, work)

    scenes = [(f"{t} {1000 + k}", ["--family", t, "--seed", str(1000 + k), "--width", "240", "--height", "180",
                                   "--objects", "7", "--noise-hz", "0.1", "--duration-s", str(a.duration_s)])
              for t in TYPES for k in range(a.seeds)]
    scenes += [(f"paper-{m} 1", ["--scene", m, "--seed", "1", "--duration-s", str(a.duration_s)]) for m in PAPER]

    print(f"<!-- tests/bench/against_authors.py {a.evms} --seeds {a.seeds} --repeat {a.repeat} --duration-s {a.duration_s:g} -->")
    print("| scene | events | F authors | F --preset paper | F evms | authors s | evms s | evms speed-up |")
    print("|---|---|---|---|---|---|---|---|")
    rows = []
    for name, gen_args in scenes:
        d = os.path.join(work, name.replace(" ", "-"))
        subprocess.run([evms, "gen", *gen_args, "--out", d], check=True, stdout=subprocess.DEVNULL)
        events_txt, truth = os.path.join(d, "events.txt"), os.path.join(d, "labels.csv")
        with open(events_txt) as f:
            events = sum(1 for line in f if line[0] != "#")
        t_peer = timed([peer, events_txt, os.path.join(d, "authors.csv"), "--width", "240", "--height", "180",
                        "--fix-clamp", "1"], a.repeat)
        timed([evms, "run", events_txt, "--preset", "paper", "--out", os.path.join(d, "paper"), "--quiet"], 1)
        t_evms = timed([evms, "run", events_txt, "--out", os.path.join(d, "evms"), "--quiet"], a.repeat)
        f_peer = f_measure(evms, truth, os.path.join(d, "authors.csv"))
        f_paper = f_measure(evms, truth, os.path.join(d, "paper", "events.csv"))
        f_evms = f_measure(evms, truth, os.path.join(d, "evms", "events.csv"))
        rows.append((name, events, f_peer, f_paper, f_evms, t_peer, t_evms))
        print(f"| {name} | {events:,} | {f_peer:.3f} | {f_paper:.3f} | {f_evms:.3f} | {t_peer:.3f} | {t_evms:.3f} | "
              f"{t_peer / t_evms:.1f}x |", flush=True)

    recordings = []
    real = os.path.join(os.path.dirname(os.path.abspath(a.peer)), "data", "real")
    for name in REAL:
        path = os.path.join(real, name)
        if not os.path.isfile(path):
            continue
        d = os.path.join(work, name)
        os.makedirs(d, exist_ok=True)
        csv = subprocess.run([evms, "run", path, "--out", "-", "--quiet"], check=True, capture_output=True, text=True).stdout
        lines = csv.splitlines()
        width, height = (int(v) for v in lines[0].split()[-1].split("x"))
        events_txt = os.path.join(d, "events.txt")
        with open(events_txt, "w") as f:
            for row in lines[2:]:
                t, x, y, p = row.split(",")[:4]
                f.write(f"{int(t) // 1000000}.{int(t) % 1000000:06d} {x} {y} {p}\n")
        t_peer = timed([peer, events_txt, os.path.join(d, "authors.csv"), "--width", str(width), "--height", str(height),
                        "--fix-clamp", "1"], a.repeat)
        t_evms = timed([evms, "run", path, "--out", os.path.join(d, "evms"), "--quiet"], a.repeat)
        recordings.append((name, len(lines) - 2, t_peer, t_evms))
    if recordings:
        print()
        print("| recording | events | authors s (events.txt) | evms s (the recording) | evms speed-up |")
        print("|---|---|---|---|---|")
        for name, n, t_peer, t_evms in recordings:
            print(f"| {name} | {n:,} | {t_peer:.3f} | {t_evms:.3f} | {t_peer / t_evms:.1f}x |")

    diffs = [abs(r[3] - r[2]) for r in rows]
    events = sum(r[1] for r in rows)
    peer_s, evms_s = sum(r[5] for r in rows), sum(r[6] for r in rows)
    print()
    print(f"--preset paper against the authors' code: mean |dF| {statistics.mean(diffs):.3f}, largest {max(diffs):.3f}")
    print(f"mean F: authors {statistics.mean(r[2] for r in rows):.3f}, --preset paper {statistics.mean(r[3] for r in rows):.3f}, "
          f"evms {statistics.mean(r[4] for r in rows):.3f}")
    print(f"whole processes: authors {events / peer_s / 1e3:.0f} k events/s, evms {events / evms_s / 1e3:.0f} k events/s "
          f"({peer_s / evms_s:.1f}x)")
    if not a.keep:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
