#!/usr/bin/python3
"""What the ice40 core would need as firmware on a soft RISC-V CPU beside the UP5K's filter:

    tests/bench/soft_cpu.py build/bin/evms [--events 6000] [--labels-only]

It compiles the core (hls::Core<Ice40Shape>, the source every build of it shares) for RV32IM
with Debian's bare cross compiler, runs it under qemu-riscv32 on the first events of a generated
128x128 rotation scene at the ice40 build's registers, checks that its labels equal the host
build's, and prints the image's sizes, the stack it used, and the instructions it executed an
event with their mix. Needs gcc-riscv64-unknown-elf, picolibc-riscv64-unknown-elf (memcpy and
memset) and qemu-user, which evms itself does not (apt install them first); without them it says
so and exits with 77, which ctest counts as skipped (SoftCpu.LabelsAsTheHostBuild in
tests/CMakeLists.txt runs it with --labels-only). docs/rtl.md ("What fits an iCE40 UP5K") gives
the figures.
"""
import argparse
import collections
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
CROSS = "riscv64-unknown-elf-"
PICOLIBC = "/usr/lib/picolibc/riscv64-unknown-elf/lib/rv32im/ilp32/libc.a"


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw).stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("evms", help="the evms binary of a build (its build folder has types/libevms_types.a)")
    ap.add_argument("--events", type=int, default=6000)
    ap.add_argument("--labels-only", action="store_true", help="check the labels only; no sizes, no instruction count")
    args = ap.parse_args()
    missing = [t for t in (CROSS + "g++", "qemu-riscv32") if shutil.which(t) is None]
    if missing or not os.path.exists(PICOLIBC):
        print("soft_cpu.py: skipped: needs gcc-riscv64-unknown-elf, picolibc-riscv64-unknown-elf and qemu-user "
              f"(missing: {', '.join(missing + ([PICOLIBC] if not os.path.exists(PICOLIBC) else []))})")
        sys.exit(77)
    types_lib = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(args.evms))), "types", "libevms_types.a")
    with tempfile.TemporaryDirectory() as tmp:
        run([args.evms, "gen", "--scene", "rotation", "--width", "128", "--height", "128", "--duration-s", "1",
             "--out", os.path.join(tmp, "scene")])
        host_ref = os.path.join(tmp, "host_reference")
        run(["g++", "-std=c++20", "-O2", "-I", REPO, os.path.join(HERE, "soft_cpu", "host_reference.cpp"), types_lib,
             "-o", host_ref])
        def firmware(events):
            """The firmware over the scene's first `events` events, and the host's labels' checksum."""
            folder = os.path.join(tmp, str(events))
            os.mkdir(folder)
            checksum = run([host_ref, os.path.join(tmp, "scene", "events.txt"), str(events),
                            os.path.join(folder, "scene.h")]).strip()
            elf = os.path.join(folder, "firmware.elf")
            run([CROSS + "g++", "-march=rv32im", "-mabi=ilp32", "-O2", "-std=c++17", "-ffreestanding", "-fno-exceptions",
                 "-fno-rtti", "-nostdlib", "-nostdinc++", "-isystem", os.path.join(HERE, "soft_cpu", "include"), "-I",
                 REPO, "-I", folder, "-static", "-Wl,--no-warn-rwx-segments", "-T",
                 os.path.join(HERE, "soft_cpu", "firmware.ld"), os.path.join(HERE, "soft_cpu", "firmware.cpp"), PICOLIBC,
                 "-lgcc", "-o", elf])
            return elf, checksum

        elf, host_checksum = firmware(args.events)
        checksum, stack = run(["qemu-riscv32", elf]).split()
        if checksum != host_checksum:
            sys.exit(f"soft_cpu.py: the RV32 core's labels differ from the host's (checksum {checksum} against {host_checksum})")
        print(f"labels       equal to the host build's on {args.events} events (checksum {checksum})")
        if args.labels_only:
            return

        sections = {}
        for line in run([CROSS + "size", "-A", elf]).splitlines():
            parts = line.split()
            if len(parts) == 3 and parts[1].isdigit():
                sections[parts[0]] = int(parts[1])
        symbols = {}
        for line in run([CROSS + "nm", "-S", elf]).splitlines():
            parts = line.split()
            if len(parts) == 4:
                symbols[parts[3]] = int(parts[1], 16)
        events_bytes = symbols["_ZL7kEvents"]
        state = symbols["_ZL4core"]
        print(f"code         {sections['.text']} bytes")
        print(f"constants    {sections['.rodata'] - events_bytes} bytes (the scene's events, {events_bytes} more, left out)")
        print(f"data         {sections['.data']} bytes (this harness's label queue)")
        print(f"core state   {state} bytes (Core<Ice40Shape>, its filter's timestamps included)")
        print(f"stack        {stack} bytes used")

        def executed_mnemonics(elf):
            """How many times each mnemonic executed: each trace line's address (one instruction a
            block) looked up in the disassembly."""
            mnemonic = {}
            for line in run([CROSS + "objdump", "-d", "--no-show-raw-insn", elf]).splitlines():
                parts = line.split()
                if len(parts) >= 2 and parts[0].endswith(":") and all(c in "0123456789abcdef" for c in parts[0][:-1]):
                    mnemonic[int(parts[0][:-1], 16)] = parts[1]
            counts = collections.Counter()
            trace = subprocess.Popen(["qemu-riscv32", "-singlestep", "-d", "nochain,exec", "-D", "/dev/stderr", elf],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            for line in trace.stderr:
                if line.startswith("Trace"):
                    counts[mnemonic.get(int(line.split("[")[1].split("/")[1], 16), "?")] += 1
            trace.wait()
            return counts

        # Per event: the run over every event less a run over one, which starts the same way (the
        # statics' constructors, the filter's memory cleared) and differs only in where its
        # events array lies, so the two are compared by mnemonic, not by address.
        by_mnemonic = executed_mnemonics(elf)
        by_mnemonic.subtract(executed_mnemonics(firmware(1)[0]))
        per_event = args.events - 1
        kinds = collections.Counter()
        for m, n in by_mnemonic.items():
            if m.startswith(("mul",)):
                kinds["multiply"] += n
            elif m.startswith(("div", "rem")):
                kinds["divide"] += n
            elif m in ("lw", "lh", "lhu", "lb", "lbu"):
                kinds["load"] += n
            elif m in ("sw", "sh", "sb"):
                kinds["store"] += n
            elif m.startswith(("b", "j")) or m in ("ret", "call", "tail"):
                kinds["branch or jump"] += n
            else:
                kinds["ALU"] += n
        total = sum(kinds.values())
        print(f"instructions {total / per_event:.0f} an event ({total} over events 2 to {args.events})")
        for kind, n in kinds.most_common():
            print(f"  {kind:<14} {100 * n / total:.1f} %  ({n / per_event:.0f} an event)")


if __name__ == "__main__":
    main()
