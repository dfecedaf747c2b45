#!/usr/bin/env python3
"""The Python module evms (host/python/evms_module.cpp) against the evms program.

ctest runs it with PYTHONPATH at the built module, EVMS_BINARY the evms program and
EVMS_SHARED_DATA the shared recordings' folder (the recordings' test skips when it is absent).
"""
import csv
import os
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest
import warnings

import numpy as np

import evms

EVMS = os.environ["EVMS_BINARY"]
SCENE = "gen://rotation?duration-s=0.3&seed=4"


def program_run(source, *args):
    """Labels and track rows that `evms run` writes for the source."""
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([EVMS, "run", source, "--out", out, *args], check=True, capture_output=True)
        with open(os.path.join(out, "events.csv")) as f:
            rows = [line for line in f if not line.startswith("#")][1:]
        labels = np.array([int(r.rsplit(",", 1)[1]) for r in rows], dtype=np.int32)
        with open(os.path.join(out, "tracks.csv")) as f:
            tracks = list(csv.DictReader(f))
    return labels, tracks


class ModuleAgainstTheProgram(unittest.TestCase):
    def setUp(self):
        self.events, self.sensor = evms.read(SCENE)

    def test_read_gives_the_events_the_program_labels(self):
        self.assertEqual(self.sensor, (240, 180))
        self.assertEqual(self.events.dtype.names, ("t", "x", "y", "p"))
        self.assertGreater(len(self.events), 5000)
        self.assertTrue(np.all(np.diff(self.events["t"]) >= 0))
        with tempfile.TemporaryDirectory() as out:
            subprocess.run([EVMS, "run", SCENE, "--out", out], check=True, capture_output=True)
            table = np.loadtxt(os.path.join(out, "events.csv"), delimiter=",", skiprows=2, dtype=np.int64)
        np.testing.assert_array_equal(table[:, 0], self.events["t"])
        np.testing.assert_array_equal(table[:, 1], self.events["x"])
        np.testing.assert_array_equal(table[:, 2], self.events["y"])
        np.testing.assert_array_equal(table[:, 3], self.events["p"])

    def test_run_labels_and_tracks_as_the_program(self):
        labels, tracks = evms.run(self.events, self.sensor)
        want_labels, want_tracks = program_run(SCENE)
        np.testing.assert_array_equal(labels, want_labels)
        self.assertGreater(len(np.unique(labels[labels >= 0])), 3)
        self.assertEqual(len(tracks), len(want_tracks))
        for got, want in zip(tracks, want_tracks):
            self.assertEqual(int(got["t_us"]), int(want["t_us"]))
            self.assertEqual(int(got["track_id"]), int(want["track_id"]))
            self.assertEqual(bool(got["confirmed"]), want["state"] == "confirmed")
            for name in ("x", "y", "vx", "vy"):
                self.assertAlmostEqual(float(got[name]), float(want[name]), delta=6e-4)
            for name in ("events", "x_min", "y_min", "x_max", "y_max"):
                self.assertEqual(int(got[name]), int(want[name]))
        # Every label is noise or a track the tracks name.
        self.assertTrue(set(np.unique(labels[labels >= 0])) <= set(tracks["track_id"]))

    def test_keyword_parameters_are_the_programs_options(self):
        labels, _ = evms.run(self.events, self.sensor, bandwidth=0.06, warm_start=False)
        want, _ = program_run(SCENE, "--bandwidth", "0.06", "--warm-start", "false")
        np.testing.assert_array_equal(labels, want)
        default, _ = evms.run(self.events, self.sensor)
        self.assertFalse(np.array_equal(labels, default))
        paper, _ = evms.run(self.events, self.sensor, preset="paper")
        want, _ = program_run(SCENE, "--preset", "paper")
        np.testing.assert_array_equal(paper, want)
        self.assertEqual(evms.parameters()["packet_size"], "3000")

    def test_the_fixed_point_core_gives_the_programs_labels(self):
        # The iCE40 build holds sensors up to 128x128; its fixed core (the iCEBreaker's board, cut
        # after its climbs, then the host core) holds the whole method in the board's packets and
        # without warm seeds, and the Arty's holds its board's sizes.
        for core, scene in (("host", SCENE), ("arty", SCENE), ("ice40", SCENE + "&width=128&height=128")):
            events, sensor = evms.read(scene)
            with warnings.catch_warnings(record=True) as caught_warnings:
                warnings.simplefilter("always")
                labels, tracks = evms.run(events, sensor, backend="fixed", core=core)
            # What a build changes of the method is said, as evms run's summary says it.
            said = [str(w.message) for w in caught_warnings if issubclass(w.category, UserWarning)]
            if core == "arty":
                self.assertEqual(len(said), 1, said)
                self.assertTrue(said[0].startswith("the arty build runs --packet-size 512 (the method's "), said)
                self.assertIn("--max-tracks 16", said[0])
            elif core == "ice40":
                self.assertEqual(said, ["the ice40 build runs --packet-size 1024 (the method's 3000), --warm-start false (the method's true)"])
            else:
                self.assertEqual(said, [], core)
            want, want_tracks = program_run(scene, "--backend", "fixed", "--core", core)
            np.testing.assert_array_equal(labels, want, err_msg=core)
            self.assertEqual(len(tracks), len(want_tracks), core)
            self.assertEqual([int(t["track_id"]) for t in want_tracks], list(tracks["track_id"]), core)
            self.assertGreater(len(np.unique(labels[labels >= 0])), 2, core)
            # Its positions are fixed-point: multiples of a power of two, which golden's are not.
            _, golden_tracks = evms.run(events, sensor)
            self.assertTrue(np.all(tracks["x"] * 2**12 == np.round(tracks["x"] * 2**12)), core)
            self.assertFalse(np.all(golden_tracks["x"] * 2**12 == np.round(golden_tracks["x"] * 2**12)), core)
        with self.assertRaises(ValueError) as caught:
            evms.run(self.events, self.sensor, backend="fixed", core="ice40")
        self.assertIn("the core is built for sensors up to 128x128, not 240x180", str(caught.exception))
        with self.assertRaises(ValueError) as caught:
            evms.run(self.events, self.sensor, backend="rtl")
        self.assertIn("the module runs golden and fixed", str(caught.exception))
        with self.assertRaises(ValueError) as caught:
            evms.run(self.events, self.sensor, backend="fixed", core="zynq")
        self.assertIn("unknown core build 'zynq'", str(caught.exception))

    def test_any_structured_array_with_the_four_fields(self):
        # tonic's layout: int64 fields in another order.
        other = np.zeros(len(self.events), dtype=[("x", "<i8"), ("y", "<i8"), ("p", "<i8"), ("t", "<i8")])
        for name in ("t", "x", "y", "p"):
            other[name] = self.events[name]
        np.testing.assert_array_equal(evms.run(other, self.sensor)[0], evms.run(self.events, self.sensor)[0])

    def test_bad_input_is_one_line_naming_where(self):
        cases = []
        outside = self.events.copy()
        outside["x"][7] = 240
        cases.append((outside, (240, 180), {}, "events[7]: (240,%d) is outside the 240x180 sensor" % outside["y"][7]))
        unsorted = self.events.copy()
        unsorted["t"][9] = unsorted["t"][8] - 1
        cases.append((unsorted, (240, 180), {}, "events[9]: t=%d us is earlier than the event before it" % unsorted["t"][9]))
        polarity = self.events.copy()
        polarity["p"][3] = 2
        cases.append((polarity, (240, 180), {}, "events[3]: polarity 2 is not 0 (OFF) or 1 (ON)"))
        cases.append((self.events[["t", "x", "y"]], (240, 180), {}, "events: no field 'p'"))
        cases.append((self.events, (0, 180), {}, "sensor: 0x180 is not a sensor size"))
        cases.append((self.events, (240, 180), {"bandwdith": 0.1}, "unknown parameter 'bandwdith'"))
        for events, sensor, params, message in cases:
            with self.assertRaises(ValueError) as caught:
                evms.run(events, sensor, **params)
            self.assertIn(message, str(caught.exception))
            self.assertNotIn("\n", str(caught.exception))
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cut.aedat")
            with open(path, "wb") as f:
                f.write(b"#!AER-DAT2.0\r\n\x00\x00\x01")
            with self.assertRaises(ValueError) as caught:
                evms.read(path)
            self.assertEqual(str(caught.exception), path + ": byte 14: truncated record (3 of 8 bytes)")
            # A text file without a size: it is assumed, and said.
            path = os.path.join(d, "events.txt")
            with open(path, "w") as f:
                f.write("0.000001 3 4 1\n0.000002 100 6 0\n")
            with self.assertWarns(UserWarning) as warned:
                _, sensor = evms.read(path)
            self.assertIn(path + ": sensor %dx%d assumed" % sensor, str(warned.warning))
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                self.assertEqual(evms.read(path, width=128, height=128)[1], (128, 128))
        with self.assertRaises(ValueError) as caught:
            evms.read("usb://dvs128")
        self.assertIn("a live source has no end (evms.stream reads it in chunks)", str(caught.exception))


def free_udp_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Streams(unittest.TestCase):
    def setUp(self):
        self.events, self.sensor = evms.read(SCENE)

    def test_a_stream_in_chunks_is_the_whole_source(self):
        stream = evms.stream(SCENE, chunk=1000)
        self.assertEqual(stream.sensor, self.sensor)
        self.assertEqual(stream.format, "generated scene")
        chunks = list(stream)
        self.assertGreater(len(chunks), 50)
        self.assertTrue(all(0 < len(c) <= 1000 for c in chunks))
        np.testing.assert_array_equal(np.concatenate(chunks), self.events)
        self.assertEqual(stream.sensor, self.sensor)  # still known at the end
        self.assertEqual(list(stream), [])
        # Replayed at 20 times its pace, through a live source's buffer and thread.
        started = time.monotonic()
        replay = evms.stream(SCENE, realtime=True, speed=20)
        np.testing.assert_array_equal(np.concatenate(list(replay)), self.events)
        self.assertGreaterEqual(time.monotonic() - started, (self.events["t"][-1] - self.events["t"][0]) / 20e6)
        self.assertEqual(replay.dropped, 0)
        self.assertEqual(replay.reordered, 0)
        with self.assertRaises(ValueError) as caught:
            evms.stream(SCENE, chunk=0)
        self.assertIn("chunk: 0 events", str(caught.exception))

    def test_late_events_are_put_in_order_and_counted(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "late.csv")
            with open(path, "w") as f:
                f.write("t_us,x,y,p\n10,1,1,1\n30,2,1,0\n20,3,1,1\n40,4,1,1\n35,5,1,0\n")
            stream = evms.stream(path, width=8, height=8, chunk=2)
            chunks = list(stream)
            self.assertEqual(stream.reordered, 2)
            self.assertEqual(list(np.concatenate(chunks)["t"]), [10, 20, 30, 35, 40])

    def test_part_of_a_source_as_the_programs_options_take_it(self):
        t = self.events["t"]
        part, _ = evms.read(SCENE, start_us=50000, duration_us=100000)
        np.testing.assert_array_equal(part, self.events[(t >= t[0] + 50000) & (t < t[0] + 150000)])
        np.testing.assert_array_equal(np.concatenate(list(evms.stream(SCENE, limit=1234, chunk=500))), self.events[:1234])
        cropped, sensor = evms.read(SCENE, roi=(10, 20, 100, 50))
        self.assertEqual(sensor, (100, 50))
        inside = self.events[(self.events["x"] >= 10) & (self.events["x"] < 110) & (self.events["y"] >= 20) & (self.events["y"] < 70)]
        np.testing.assert_array_equal(cropped["x"], inside["x"] - 10)
        np.testing.assert_array_equal(cropped["y"], inside["y"] - 20)
        busiest = np.bincount(self.events["y"].astype(np.int64) * 240 + self.events["x"]).argmax()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "hot.txt")
            with open(path, "w") as f:
                f.write("%d,%d\n" % (busiest % 240, busiest // 240))
            masked, _ = evms.read(SCENE, hot_pixels=path)
        at = (self.events["x"] == busiest % 240) & (self.events["y"] == busiest // 240)
        np.testing.assert_array_equal(masked, self.events[~at])
        for bad, message in [({"roi": (200, 0, 100, 5)}, "reaches outside the 240x180 sensor"), ({"limit": -1}, "limit: -1 (0 or more)")]:
            with self.assertRaises(ValueError) as caught:
                evms.read(SCENE, **bad)
            self.assertIn(message, str(caught.exception))

    def test_a_tracker_fed_chunks_gives_what_run_gives(self):
        for backend in ("golden", "fixed"):
            labels, tracks = evms.run(self.events, self.sensor, backend=backend, bandwidth=0.06)
            tracker = evms.Tracker(self.sensor, backend=backend, bandwidth=0.06)
            done, updates = [], []
            for first in range(0, len(self.events), 777):
                labelled, new = tracker.push(self.events[first:first + 777])
                done.append(labelled), updates.append(new)
            # Labels come as packets close, so some lag behind the events pushed.
            self.assertLess(sum(len(d) for d in done), len(self.events), backend)
            labelled, new = tracker.finish()
            done.append(labelled), updates.append(new)
            done, updates = np.concatenate(done), np.concatenate(updates)
            self.assertEqual(done.dtype.names, ("t", "x", "y", "p", "label"))
            for name in ("t", "x", "y", "p"):
                np.testing.assert_array_equal(done[name], self.events[name], err_msg=backend)
            np.testing.assert_array_equal(done["label"], labels, err_msg=backend)
            np.testing.assert_array_equal(updates, tracks, err_msg=backend)
            self.assertEqual(tracker.stats["events_in"], len(self.events), backend)
            self.assertGreater(tracker.stats["packets"], 10, backend)
            self.assertEqual(len(tracker.finish()[0]), 0, backend)
            with self.assertRaises(ValueError) as caught:
                tracker.push(self.events[:10])
            self.assertIn("the Tracker has finished", str(caught.exception))
        tracker = evms.Tracker(self.sensor)
        tracker.push(self.events[100:200])
        with self.assertRaises(ValueError) as caught:
            tracker.push(self.events[:10])
        self.assertEqual(str(caught.exception), "events[0]: t=%d us is earlier than the last event pushed before it (%d us)"
                         % (self.events["t"][0], self.events["t"][199]))

    def test_a_udp_stream_as_it_arrives(self):
        # jAER AEUnicast datagrams (host/read/live/jaer_datagram.h): a big-endian sequence number,
        # then {address, timestamp} records; a DVS128 address is y << 8 | x << 1 | polarity.
        port = free_udp_port()
        stream = evms.stream("udp://127.0.0.1:%d?camera=dvs128&idle-s=1" % port, chunk=100)
        self.assertEqual(stream.sensor, (128, 128))
        sent = [(1000 + 7 * i, (3 * i) % 128, (5 * i) % 128, i % 2) for i in range(600)]

        def send():
            with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
                for seq, first in enumerate(range(0, len(sent), 50)):
                    records = b"".join(struct.pack(">ii", y << 8 | x << 1 | p, t) for t, x, y, p in sent[first:first + 50])
                    s.sendto(struct.pack(">i", seq) + records, ("127.0.0.1", port))
                    time.sleep(0.01)

        sender = threading.Thread(target=send)
        sender.start()
        got = np.concatenate(list(stream))
        sender.join()
        self.assertEqual([tuple(int(v) for v in e) for e in got], sent)

    def test_ctrl_c_reaches_python_while_a_live_source_is_quiet(self):
        port = free_udp_port()
        script = ("import evms\nprint('open', flush=True)\n"
                  "for chunk in evms.stream('udp://127.0.0.1:%d?camera=dvs128'):\n    pass\n" % port)
        with subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as child:
            try:
                self.assertEqual(child.stdout.readline().strip(), "open")
                time.sleep(0.5)
                child.send_signal(signal.SIGINT)
                _, stderr = child.communicate(timeout=10)
            finally:
                child.kill()
        self.assertNotEqual(child.returncode, 0)
        self.assertIn("KeyboardInterrupt", stderr)


class Scores(unittest.TestCase):
    def test_score_is_evms_metrics(self):
        with tempfile.TemporaryDirectory() as d:
            subprocess.run([EVMS, "gen", "--family", "crossing", "--seed", "3", "--duration-s", "0.4", "--out", d], check=True, capture_output=True)
            events, sensor = evms.read(os.path.join(d, "events.txt"))
            truth = np.loadtxt(os.path.join(d, "labels.csv"), delimiter=",", skiprows=2, dtype=np.int64)
            np.testing.assert_array_equal(truth[:, 0], events["t"])
            labels, _ = evms.run(events, sensor)
            subprocess.run([EVMS, "run", os.path.join(d, "events.txt"), "--out", os.path.join(d, "run")], check=True, capture_output=True)
            for args, kwargs in [(["--chunk-us", "10000"], {"chunk_us": 10000}), ([], {}), (["--chunk-events", "1000"], {"chunk_events": 1000})]:
                printed = subprocess.run([EVMS, "metrics", "--truth", os.path.join(d, "labels.csv"), "--pred", os.path.join(d, "run", "events.csv"), *args],
                                         check=True, capture_output=True, text=True).stdout.split()
                got = evms.score(events, truth[:, 4], labels, **kwargs)
                for name, want in zip(("ari", "nmi", "precision", "recall", "f"), printed):
                    self.assertAlmostEqual(got[name], float(want), delta=1e-6, msg=name + " " + str(args))
                self.assertGreater(got["chunks"], 10)
            self.assertLess(evms.score(events, truth[:, 4], np.roll(labels, 500), chunk_us=10000)["f"], got["f"])
            self.assertEqual(evms.score(events, truth[:, 4], truth[:, 4], chunk_us=10000)["f"], 1.0)
            with self.assertRaises(ValueError) as caught:
                evms.score(events, truth[:-1, 4], labels)
            self.assertIn("one label an event (%d events)" % len(events), str(caught.exception))
            with self.assertRaises(ValueError):
                evms.score(events, truth[:, 4], labels, chunk_us=10000, chunk_events=100)


class Generate(unittest.TestCase):
    def test_generate_gives_what_evms_gen_writes(self):
        events, labels, truth, sensor = evms.generate("gen://family/crossing?seed=3&duration-s=0.4")
        self.assertEqual(sensor, evms.read("gen://family/crossing?seed=3&duration-s=0.4")[1])
        with tempfile.TemporaryDirectory() as d:
            subprocess.run([EVMS, "gen", "--family", "crossing", "--seed", "3", "--duration-s", "0.4", "--out", d], check=True, capture_output=True)
            want = np.loadtxt(os.path.join(d, "labels.csv"), delimiter=",", skiprows=2, dtype=np.int64)
            gt = np.loadtxt(os.path.join(d, "gt_tracks.csv"), delimiter=",", skiprows=1)
        for column, name in enumerate(("t", "x", "y", "p")):
            np.testing.assert_array_equal(events[name], want[:, column])
        np.testing.assert_array_equal(labels, want[:, 4])
        self.assertGreater(len(np.unique(labels[labels >= 0])), 1)
        np.testing.assert_array_equal(truth["t_us"], gt[:, 0])
        np.testing.assert_array_equal(truth["object"], gt[:, 1])
        np.testing.assert_allclose(truth["x"], gt[:, 2], atol=6e-4)
        np.testing.assert_allclose(truth["y"], gt[:, 3], atol=6e-4)
        with self.assertRaises(ValueError) as caught:
            evms.generate("gen://family/parade?seed=3")
        self.assertIn("parade", str(caught.exception))


class RealRecordings(unittest.TestCase):
    def test_the_shared_recordings_reference_figures(self):
        shared = os.environ.get("EVMS_SHARED_DATA", "")
        if not os.path.isdir(shared):
            self.skipTest("the shared recordings are not here (" + shared + ")")
        # ../shared/data/real/README.md: events, first and last time, ON count.
        for name, sensor, count, first, last, on in [
            ("gen3_moving_blob.evt2.raw", (640, 480), 539481, 1317888, 1367888, 367855),
            ("dvxplorer_indoor.aedat4", (320, 240), 111954, 1605537493718345, 1605537494308262, 55023),
        ]:
            events, size = evms.read(os.path.join(shared, name))
            self.assertEqual(size, sensor, name)
            self.assertEqual(len(events), count, name)
            self.assertEqual(int(events["t"][0]), first, name)
            self.assertEqual(int(events["t"][-1]), last, name)
            self.assertEqual(int(events["p"].sum()), on, name)
        labels, tracks = evms.run(*evms.read(os.path.join(shared, "gen3_moving_blob.evt2.raw")))
        want, _ = program_run(os.path.join(shared, "gen3_moving_blob.evt2.raw"))
        np.testing.assert_array_equal(labels, want)


if __name__ == "__main__":
    unittest.main()
