#!/usr/bin/python3
"""evms on scenes from a second event simulator, one that shares no code or model with
host/gen, beside `evms run --preset paper` and the authors' own program:

    tests/bench/other_simulator.py build/bin/evms [--seeds 6] [--sensor 240x180] [--jobs 2] [--evms-args "..."]
        [--noise-share 0.05] [--speed 1] [--threshold 0.2] [--shapes 7] [--size 1] [--duration-s 1]
        [--without-authors] [--min-lead L]

Every default of evms was chosen on host/gen's scene family, so a score on that family can
carry what that generator does and a real sensor does not. This simulator renders shapes as
signed-distance fields with a one-pixel soft edge over a uniform background, and makes events
the way a DVS pixel does: each pixel fires when its log intensity has moved a contrast threshold
away from the level of its last event (thresholds drawn per pixel and per polarity, N(0.2, 0.03)
by default),
at the time the level was crossed (interpolated between frames 0.4 ms apart), and not again
within a 0.5 ms refractory period. An event's label is the shape whose visible coverage of that
pixel changed most over the frame; then uniform background activity is added as 5 % of the
events, labelled noise. Seven shapes of nine kinds (disk, square, triangle, thin bar, ring,
cross, L, star, ellipse; 5-44 px across on 240x180, a seventh of them 2.5-4 px, a quarter low
contrast) and four motions of one second:
  pan    the camera moves sideways on two sinusoids;
  spin   the camera rolls about the sensor's centre, up to 1.6 rad either way;
  zoom6  scale 0.7-1.3x with roll and translation (6-DoF);
  cross  a still camera and shapes in pairs on straight paths that meet, one shape still.
--noise-share, --speed (every motion sped up or slowed down), --threshold (the contrast
thresholds' mean; a lower one makes more events an edge), --shapes (how many) and --size (the
shapes' sizes, all but the smallest seventh, times the default) vary the scenes away from the
settings the tables in docs/sweep.md were measured at, to see whether a lead holds beyond them.
--min-lead L exits with status 1, naming the motion, when evms's mean F on a motion is not at
least L above `--preset paper`'s (and the authors' program's, when it runs).

Each scene is scored as `evms metrics --chunk-us 10000` scores (F over 10 ms chunks, noise as
singletons). The authors' program is built from ../shared/peer (g++ and Debian's
libopencv-core-dev); without that folder its column is left out, saying so. The simulator
needs NumPy (Debian's python3-numpy).
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from multiprocessing import Pool

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from against_authors import build_peer, f_measure  # noqa: E402

TYPES = ["pan", "spin", "zoom6", "cross"]
# "F touching merged": the truth scored with the shapes whose events come within this many
# pixels of each other in a 10 ms chunk merged (`evms metrics --touching-px`), what a clustering
# that holds touching shapes together scores at best.
TOUCHING_PX = 2
KINDS = ["disk", "square", "triangle", "bar", "ring", "cross", "ell", "star", "ellipse"]
# The settings --noise-share, --speed, --threshold, --shapes, --size and --duration-s move the
# scenes away from, in that order, with the letter each puts in a moved scene's folder name.
DEFAULT_VARIANT = {"noise-share": 0.05, "speed": 1.0, "threshold": 0.2, "shapes": 7, "size": 1.0, "duration-s": 1.0}
VARIANT_LETTER = {"noise-share": "n", "speed": "v", "threshold": "c", "shapes": "o", "size": "s", "duration-s": "d"}


def box_distance(np, u, v, a, b):
    """Signed distance (px, negative inside) of a box of half-sides a and b centred at the origin."""
    qx, qy = np.abs(u) - a, np.abs(v) - b
    return np.hypot(np.maximum(qx, 0), np.maximum(qy, 0)) + np.minimum(np.maximum(qx, qy), 0)


def sdf(np, kind, u, v, s):
    """Signed distance (px, negative inside) of a shape of size s centred at the origin."""
    def box(a, b, shift_u=0.0, shift_v=0.0):
        return box_distance(np, u + shift_u, v + shift_v, a, b)

    def triangle(r, turn):
        # An equilateral triangle as the largest of its three edges' signed distances.
        d = None
        for a in (np.pi / 2, np.pi / 2 + 2 * np.pi / 3, np.pi / 2 + 4 * np.pi / 3):
            e = np.cos(turn + a) * u + np.sin(turn + a) * v - r / 2
            d = e if d is None else np.maximum(d, e)
        return d

    if kind == "disk":
        return np.hypot(u, v) - s
    if kind == "square":
        return box(s * 0.85, s * 0.85)
    if kind == "triangle":
        return triangle(s * 1.2, 0.0)
    if kind == "bar":
        return box(s * 1.3, max(1.5, s * 0.18))
    if kind == "ring":
        return np.abs(np.hypot(u, v) - s) - max(1.5, s * 0.2)
    if kind == "cross":
        return np.minimum(box(s, s * 0.25), box(s * 0.25, s))
    if kind == "ell":
        return np.minimum(box(s * 0.3, s, shift_u=s * 0.35), box(s, s * 0.3, shift_v=-s * 0.7))
    if kind == "star":
        return np.minimum(triangle(s * 1.2, 0.0), triangle(s * 1.2, np.pi))
    if kind == "ellipse":
        return np.hypot(u / 1.6, v) - s * 0.7
    raise ValueError(kind)


def pixel_events(np, rng, width, height, duration_s, frame_s, refractory_s, render, label_of,
                 threshold_mean=DEFAULT_VARIANT["threshold"]):
    """The events (t s, x, y, p, label) of a DVS pixel array watching render(t) -> (log intensity,
    what label_of reads) in frames frame_s apart: a pixel fires when its log intensity has moved
    its contrast threshold (drawn per pixel and polarity, N(threshold_mean, 0.15 threshold_mean))
    from the level of its last event, timed where the level was crossed, and not again within
    refractory_s. An event's label is label_of(the frame before, the frame after, ys, xs) at its
    pixel."""
    # Drawn at the mean 0.2 and scaled, so that the mean 0.2 gives the scenes docs/sweep.md measures.
    scale = threshold_mean / 0.2
    threshold_on = np.clip(rng.normal(0.2, 0.03, (height, width)), 0.08, None) * scale
    threshold_off = np.clip(rng.normal(0.2, 0.03, (height, width)), 0.08, None) * scale
    log0, seen0 = render(0.0)
    reference = log0.copy()
    last_event = np.full((height, width), -1.0)
    events = []
    for k in range(1, int(duration_s / frame_s) + 1):
        t1 = k * frame_s
        log1, seen1 = render(t1)
        change = log1 - reference
        threshold = np.where(change > 0, threshold_on, threshold_off)
        crossings = np.floor(np.abs(change) / threshold).astype(int)
        ys, xs = np.nonzero(crossings)
        if len(ys):
            labels = label_of(seen0, seen1, ys, xs)
            for y, x, label in zip(ys, xs, labels):
                sign = 1 if change[y, x] > 0 else -1
                lo, hi = log0[y, x], log1[y, x]
                for m in range(1, crossings[y, x] + 1):
                    level = reference[y, x] + sign * m * threshold[y, x]
                    fraction = (level - lo) / (hi - lo) if hi != lo else 1.0
                    t = t1 - frame_s + frame_s * min(max(fraction, 0.0), 1.0)
                    if t - last_event[y, x] >= refractory_s:
                        events.append((t, x, y, 1 if sign > 0 else 0, label))
                        last_event[y, x] = t
                reference[y, x] += sign * crossings[y, x] * threshold[y, x]
        log0, seen0 = log1, seen1
    return events


def write_scene(np, rng, out, width, height, duration_s, signal, n_noise):
    """Adds n_noise events of uniform background activity (label -1) to the rows (t s, x, y, p,
    label) of signal and writes OUT/labels.csv (# sensor WxH, then t_us,x,y,p,label) and
    OUT/events.txt (the authors' program's input: t s, x, y, p)."""
    noise = np.column_stack([rng.uniform(0, duration_s, n_noise), rng.integers(0, width, n_noise),
                             rng.integers(0, height, n_noise), rng.integers(0, 2, n_noise), np.full(n_noise, -1)])
    rows = np.vstack([signal, noise])
    rows = rows[np.argsort(rows[:, 0], kind="stable")]
    t_us = np.round(rows[:, 0] * 1e6).astype(np.int64)
    ints = rows.astype(np.int64)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "events.txt"), "w") as f:
        for r, t in zip(ints, t_us):
            f.write(f"{t // 1000000}.{t % 1000000:06d} {r[1]} {r[2]} {r[3]}\n")
    with open(os.path.join(out, "labels.csv.part"), "w") as f:
        f.write(f"# sensor {width}x{height}\nt_us,x,y,p,label\n")
        for r, t in zip(ints, t_us):
            f.write(f"{t},{r[1]},{r[2]},{r[3]},{r[4]}\n")
    os.replace(os.path.join(out, "labels.csv.part"), os.path.join(out, "labels.csv"))


def simulate(job):
    """Writes DIR/labels.csv (# sensor WxH, then t_us,x,y,p,label) and DIR/events.txt."""
    import numpy as np
    motion, seed, width, height, variant, out = job
    if os.path.isfile(os.path.join(out, "labels.csv")):
        return out
    rng = np.random.default_rng(seed * 7919 + TYPES.index(motion))
    frame_s, refractory_s = 0.0004, 0.0005
    noise_share, motion_speed, threshold_mean, shape_count, size_scale, duration_s = variant
    scale = width / 240.0
    cx, cy = width / 2, height / 2
    shapes, placed = [], []
    for _ in range(shape_count):
        kind = KINDS[rng.integers(len(KINDS))]
        size = rng.uniform(2.5, 4) * scale if rng.random() < 0.15 else rng.uniform(5, 22) * scale * size_scale
        for attempt in range(400):  # apart from the shapes already placed: smaller until it fits
            px, py = rng.uniform(0.15 * width, 0.85 * width), rng.uniform(0.15 * height, 0.85 * height)
            if all(np.hypot(px - qx, py - qy) > (size + qs) * 1.3 + 4 for qx, qy, qs in placed):
                break
            if attempt % 50 == 49:
                size = max(2.5 * scale, size * 0.8)
        placed.append((px, py, size))
        if rng.random() < 0.25:
            intensity = 0.5 * np.exp(rng.choice([-1, 1]) * rng.uniform(0.28, 0.45))  # low contrast
        else:
            intensity = rng.choice([rng.uniform(0.12, 0.3), rng.uniform(0.8, 1.0)])
        speed, heading = rng.uniform(30, 90) * scale, rng.uniform(0, 2 * np.pi)
        shapes.append(dict(kind=kind, s=size, x=px, y=py, a=rng.uniform(0, 2 * np.pi), I=intensity,
                           vx=speed * np.cos(heading), vy=speed * np.sin(heading), w=rng.uniform(-2, 2)))
    if motion == "cross":
        for i in range(0, len(shapes) - 1, 2):  # the second of a pair aims where the first will be
            a, b = shapes[i], shapes[i + 1]
            tm = rng.uniform(0.25, 0.75)
            mx = np.clip(a["x"] + a["vx"] * tm, 0.2 * width, 0.8 * width)
            my = np.clip(a["y"] + a["vy"] * tm, 0.2 * height, 0.8 * height)
            a["vx"], a["vy"] = (mx - a["x"]) / tm, (my - a["y"]) / tm
            b["vx"], b["vy"] = (mx - b["x"]) / tm, (my - b["y"]) / tm
        shapes[-1]["vx"] = shapes[-1]["vy"] = shapes[-1]["w"] = 0.0
    else:  # only the camera moves
        for o in shapes:
            o["vx"] = o["vy"] = o["w"] = 0.0
    f1, f2 = rng.uniform(0.4, 0.9), rng.uniform(0.4, 0.9)
    ph1, ph2 = rng.uniform(0, 2 * np.pi, 2)
    amp = rng.uniform(14, 26) * scale

    def camera(t):  # zoom, roll, shift x, shift y (t in the motion's time: seconds times speed)
        if motion == "pan":
            return 1.0, 0.0, amp * np.sin(2 * np.pi * f1 * t + ph1), 0.7 * amp * np.sin(2 * np.pi * f2 * t + ph2)
        if motion == "spin":
            return 1.0, 1.6 * np.sin(2 * np.pi * 0.35 * t + ph1), 0.0, 0.0
        if motion == "zoom6":
            return (1.0 + 0.3 * np.sin(2 * np.pi * f1 * t + ph1), 0.5 * np.sin(2 * np.pi * f2 * t + ph2),
                    0.4 * amp * np.sin(2 * np.pi * 0.7 * t), 0.3 * amp * np.cos(2 * np.pi * 0.6 * t))
        return 1.0, 0.0, 0.0, 0.0

    yy, xx = np.mgrid[0:height, 0:width].astype(np.float64)

    def render(t):
        """Log intensity, and each shape's visible coverage of every pixel (later shapes on top)."""
        t = t * motion_speed
        zoom, roll, dx, dy = camera(t)
        c, s = np.cos(roll), np.sin(roll)
        image = np.full((height, width), 0.5)
        covers = []
        for o in shapes:
            ox, oy = o["x"] + o["vx"] * t, o["y"] + o["vy"] * t
            wx, wy = ox - cx, oy - cy
            ix, iy = cx + zoom * (c * wx - s * wy) + dx, cy + zoom * (s * wx + c * wy) + dy
            turn = o["a"] + o["w"] * t + roll
            u0, v0 = xx - ix, yy - iy
            u = (np.cos(turn) * u0 + np.sin(turn) * v0) / zoom
            v = (-np.sin(turn) * u0 + np.cos(turn) * v0) / zoom
            cover = np.clip(0.5 - sdf(np, o["kind"], u, v, o["s"]) * zoom, 0, 1)
            covers.append(cover)
            image = image * (1 - cover) + o["I"] * cover
        visible = np.empty((len(shapes), height, width))
        above = np.ones((height, width))
        for i in range(len(shapes) - 1, -1, -1):
            visible[i] = covers[i] * above
            above = above * (1 - covers[i])
        return np.log(image), visible

    events = pixel_events(np, rng, width, height, duration_s, frame_s, refractory_s, render,
                          lambda visible0, visible1, ys, xs: np.argmax(np.abs(visible1[:, ys, xs] - visible0[:, ys, xs]), axis=0),
                          threshold_mean)
    signal = np.array(events, dtype=np.float64).reshape(-1, 5)
    write_scene(np, rng, out, width, height, duration_s, signal, int(len(signal) * noise_share / (1 - noise_share)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("evms")
    ap.add_argument("--seeds", type=int, default=6, help="scenes of each motion (seeds 1..N)")
    ap.add_argument("--sensor", default="240x180", help="WxH")
    ap.add_argument("--jobs", type=int, default=2, help="scenes simulated at once")
    ap.add_argument("--peer", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../../shared/peer"))
    ap.add_argument("--keep", help="keep the scenes and outputs in this folder (and reuse its scenes)")
    ap.add_argument("--evms-args", default="", help="options added to the defaults' run, such as '--bandwidth 0.03'")
    ap.add_argument("--noise-share", type=float, default=DEFAULT_VARIANT["noise-share"], help="background activity's share of the events")
    ap.add_argument("--speed", type=float, default=DEFAULT_VARIANT["speed"], help="every motion's speed, times the default")
    ap.add_argument("--threshold", type=float, default=DEFAULT_VARIANT["threshold"], help="the contrast thresholds' mean (log intensity)")
    ap.add_argument("--shapes", type=int, default=DEFAULT_VARIANT["shapes"], help="shapes in each scene")
    ap.add_argument("--size", type=float, default=DEFAULT_VARIANT["size"], help="the shapes' sizes (all but the smallest), times the default")
    ap.add_argument("--duration-s", type=float, default=DEFAULT_VARIANT["duration-s"], help="each scene's length (s)")
    ap.add_argument("--without-authors", action="store_true", help="leave the authors' program out")
    ap.add_argument("--min-lead", type=float, help="fail unless evms's mean F on every motion is this much above the others'")
    a = ap.parse_args()
    if not 0 <= a.noise_share < 1 or min(a.speed, a.threshold, a.size, a.duration_s) <= 0 or a.shapes < 2:
        sys.exit("other_simulator: --noise-share must lie in [0, 1), --speed, --threshold, --size and --duration-s above 0, "
                 "--shapes 2 or more")
    try:
        import numpy  # noqa: F401
    except ImportError:
        sys.exit("other_simulator: the simulator needs NumPy: apt-get install python3-numpy")
    width, height = (int(v) for v in a.sensor.split("x"))
    evms = os.path.abspath(a.evms)
    work = a.keep or tempfile.mkdtemp(prefix="evms_other_sim_")
    os.makedirs(work, exist_ok=True)
    peer = None
    if a.without_authors:
        print("other_simulator: --without-authors: the authors' column is left out")
    elif os.path.isfile(os.path.join(a.peer, "authors_clustering.cpp")):
        peer = build_peer(a.peer, work)
    else:
        print(f"other_simulator: {os.path.normpath(a.peer)} holds no authors_clustering.cpp: the authors' column is left out")

    variant = (a.noise_share, a.speed, a.threshold, a.shapes, a.size, a.duration_s)
    moved = {name: value for name, value in zip(DEFAULT_VARIANT, variant) if value != DEFAULT_VARIANT[name]}
    # Only scenes away from the defaults carry their settings in the folder's name.
    tag = "".join(f"-{VARIANT_LETTER[name]}{value:g}" for name, value in zip(DEFAULT_VARIANT, variant)) if moved else ""
    jobs = [(m, s, width, height, variant, os.path.join(work, f"{m}-{s}-{a.sensor}{tag}"))
            for m in TYPES for s in range(1, a.seeds + 1)]
    with Pool(a.jobs) as pool:
        pool.map(simulate, jobs)

    extra = f" --evms-args='{a.evms_args}'" if a.evms_args else ""
    extra += "".join(f" --{name} {value:g}" for name, value in moved.items())
    print(f"<!-- tests/bench/other_simulator.py {a.evms} --seeds {a.seeds} --sensor {a.sensor}{extra} -->")
    print("| scene | events | F authors | F --preset paper | F evms | evms P | evms R | F touching merged |")
    print("|---|---|---|---|---|---|---|---|")
    rows = []
    for motion, seed, _, _, _, d in jobs:
        truth = os.path.join(d, "labels.csv")
        with open(truth) as f:
            events = sum(1 for line in f) - 2
        f_peer = None
        if peer:
            subprocess.run([peer, os.path.join(d, "events.txt"), os.path.join(d, "authors.csv"), "--width", str(width),
                            "--height", str(height), "--fix-clamp", "1"], check=True, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
            f_peer = f_measure(evms, truth, os.path.join(d, "authors.csv"))
        for preset, extra in (("paper", []), ("evms", a.evms_args.split())):
            subprocess.run([evms, "run", truth, "--preset", preset, *extra, "--out", os.path.join(d, preset), "--quiet"],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        f_paper = f_measure(evms, truth, os.path.join(d, "paper", "events.csv"))
        lines = subprocess.run([evms, "metrics", "--truth", truth, "--pred", os.path.join(d, "evms", "events.csv"), "--chunk-us",
                                "10000", "--touching-px", str(TOUCHING_PX)], check=True, capture_output=True, text=True).stdout.splitlines()
        p, r, f_evms = (float(v) for v in lines[0].split()[2:5])
        touching = next(line for line in lines if line.startswith("touching-merged "))  # "touching-merged ARI NMI P R F (...)"
        f_touching = float(touching.split()[5])
        rows.append((motion, f_peer, f_paper, f_evms, f_touching))
        authors = f"{f_peer:.3f}" if f_peer is not None else "-"
        print(f"| {motion} {seed} | {events:,} | {authors} | {f_paper:.3f} | {f_evms:.3f} | {p:.3f} | {r:.3f} | {f_touching:.3f} |",
              flush=True)

    print()
    print("| motion | F authors | F --preset paper | F evms | evms ahead of the authors | F touching merged |")
    print("|---|---|---|---|---|---|")
    short = []
    for motion in TYPES:
        mine = [r for r in rows if r[0] == motion]
        mean = lambda i: statistics.mean(r[i] for r in mine)  # noqa: E731
        if peer:
            print(f"| {motion} | {mean(1):.3f} | {mean(2):.3f} | {mean(3):.3f} | {sum(r[3] > r[1] for r in mine)} of {len(mine)} | {mean(4):.3f} |")
        else:
            print(f"| {motion} | - | {mean(2):.3f} | {mean(3):.3f} | - | {mean(4):.3f} |")
        others = [("--preset paper", mean(2))] + ([("the authors' program", mean(1))] if peer else [])
        short += [f"on {motion} evms scores F {mean(3):.3f}, less than {a.min_lead:g} above {name}'s {f:.3f}"
                  for name, f in others if a.min_lead is not None and mean(3) < f + a.min_lead]
    if not a.keep:
        shutil.rmtree(work)
    for line in short:
        print(f"other_simulator: {line}", file=sys.stderr)
    sys.exit(1 if short else 0)


if __name__ == "__main__":
    main()
