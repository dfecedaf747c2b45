#!/usr/bin/python3
"""Soak test of a live source: a jAER AEUnicast sender on localhost at a fixed event rate for a
set time, into `evms run udp://...`. Reports the events sent, processed and dropped (they must
add up: sent = processed + dropped + lost on the socket), the peak RSS of each minute, and the
latency line evms prints.

    tests/bench/udp_soak.py build/bin/evms --minutes 10 --rate 2000000

The scene: four squares of 12 px moving across a DVS128 sensor, their edges firing, plus 5 %
uniform noise, cut into datagrams of 1,000 records (8 kB) with sequence numbers.
"""
import argparse
import os
import re
import socket
import struct
import subprocess
import sys
import time

import numpy as np


def scene(events_per_ms, ms):
    """(t_us, x, y, p) of one `ms`-millisecond loop of the scene, events_per_ms a millisecond."""
    out = []
    squares = [(10, 20, 40.0, 0.0), (80, 30, -30.0, 20.0), (30, 90, 25.0, -25.0), (100, 100, -45.0, -10.0)]
    for m in range(ms):
        t0 = m * 1000
        for k in range(events_per_ms):
            t = t0 + k * 1000 // events_per_ms
            if k % 20 == 19:  # noise
                out.append((t, (k * 37 + m * 11) % 128, (k * 53 + m * 7) % 128, k & 1))
                continue
            sx, sy, vx, vy = squares[k % 4]
            cx = (sx + vx * t * 1e-6) % 116
            cy = (sy + vy * t * 1e-6) % 116
            edge = (k // 4) % 48
            side, pos = edge // 12, edge % 12
            x, y = [(cx + pos, cy), (cx + 11, cy + pos), (cx + pos, cy + 11), (cx, cy + pos)][side]
            out.append((t, int(x) % 128, int(y) % 128, 1 if side < 2 else 0))
    return out


def records_of(events):
    """{address, timestamp} records with DVS128 addresses."""
    return np.array([((y << 8) | (x << 1) | p, t) for t, x, y, p in events], dtype=np.uint64)


def datagrams(events, records, per_datagram, loop_us, loops):
    """Big-endian records behind sequence numbers, the scene looped."""
    seq = 0
    for loop in range(loops):
        block = records.copy()
        block[:, 1] = (block[:, 1] + loop * loop_us) & 0xFFFFFFFF
        wire = block.astype(">u4")
        for i in range(0, len(events), per_datagram):
            chunk = wire[i:i + per_datagram]
            yield (events[i][0] + loop * loop_us, struct.pack(">I", seq) + chunk.tobytes(), len(chunk))
            seq += 1


def rss_kb(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def main():
    a = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    a.add_argument("evms")
    a.add_argument("--minutes", type=float, default=10)
    a.add_argument("--rate", type=int, default=2000000, help="events per second sent")
    a.add_argument("--backend", default="golden")
    a.add_argument("--port", type=int, default=18991)
    o = a.parse_args()

    per_ms = max(1, o.rate // 1000)
    loop_ms = 200
    events = scene(per_ms, loop_ms)
    records = records_of(events)  # before evms starts: it ends after 3 s without a datagram
    loops = max(1, int(o.minutes * 60 * 1000 / loop_ms))
    run = subprocess.Popen([o.evms, "run", f"udp://127.0.0.1:{o.port}?camera=dvs128&idle-s=3", "--backend", o.backend, "--quiet"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)  # let it bind
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4 << 20)
    sent = 0
    start = time.monotonic()
    minute_peaks = {}
    next_sample = start
    for t_us, payload, n in datagrams(events, records, 1000, loop_ms * 1000, loops):
        due = start + t_us * 1e-6
        now = time.monotonic()
        if due > now:
            time.sleep(due - now)
        sock.sendto(payload, ("127.0.0.1", o.port))
        sent += n
        if now >= next_sample:
            minute = int((now - start) // 60)
            minute_peaks[minute] = max(minute_peaks.get(minute, 0), rss_kb(run.pid))
            next_sample = now + 1.0
    elapsed = time.monotonic() - start
    out, err = run.communicate(timeout=120)
    m_in = re.search(r"events in\s+([\d,]+)", out)
    m_drop = re.search(r"live\s+([\d,]+) events dropped", out)
    m_lost = re.search(r"([\d,]+) lost datagrams", out)
    m_lat = re.search(r"latency\s+(.*)", out)
    processed = int(m_in.group(1).replace(",", "")) if m_in else -1
    dropped = int(m_drop.group(1).replace(",", "")) if m_drop else -1
    lost = int(m_lost.group(1).replace(",", "")) * 1000 if m_lost else 0
    print(f"sent {sent:,} events in {elapsed:.0f} s ({sent / elapsed / 1e6:.2f} M events/s), backend {o.backend}")
    print(f"processed {processed:,}, dropped {dropped:,}, lost on the socket {lost:,} (1,000 events a datagram)")
    print(f"accounting: sent - processed - dropped - lost = {sent - processed - dropped - lost:,}")
    print("peak RSS per minute (MB): " + ", ".join(f"{m}: {kb / 1024:.1f}" for m, kb in sorted(minute_peaks.items())))
    if m_lat:
        print("latency " + m_lat.group(1))
    if run.returncode != 0:
        print(err, file=sys.stderr)
    return 0 if run.returncode == 0 and sent == processed + dropped + lost else 1


if __name__ == "__main__":
    sys.exit(main())
