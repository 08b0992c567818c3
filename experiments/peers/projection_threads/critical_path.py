#!/usr/bin/env python3
"""Where the two-thread time of `plmap project` goes, from the phase traces of an instrumented
build (phase_trace.patch; run by measure.sh).

Per phase:
  - one thread: the process CPU seconds of the phase (median over the runs);
  - two threads: its critical path, max(CPU of the calling thread, CPU of the other threads),
    and for the closure blocks the larger block's thread CPU (median over the runs).
On a machine with a free second core, the two-thread time is about the sum of the critical paths
(plus what the threads cost each other: caches, page-fault locks), so the sum predicts the
speed-up, and s = 2 path / one-thread - 1 is the serial share Amdahl's law would need for it.

Usage: critical_path.py CASE BEFORE_TAG... --after AFTER_TAG... [--changed GROUP...]
Trace files are TAG-CASE-T-ROUND.txt. Phase groups not named in --changed run the same code in
both builds: their runs are pooled (load noise is larger than their difference).
"""
import argparse, glob, re, statistics

GROUPS = [
    ("set-up (normals, kd-trees, box index, focal distances)", ["P0 setup"]),
    ("ghost rays", ["P1 rays"]),
    ("vertex preimages", ["P2 vertex preimages"]),
    ("vertex and ghost insertion (builder set-up, sheet choice)",
     ["P3a builder creation", "P3b insert vertex preimages", "P3c free preimages", "P3d insert ghost nodes"]),
    ("boundary entries", ["P4a boundary entries"]),
    ("edge walks + insertion (pipelined)", ["P4b walks+insertion"]),
    ("rim, release", ["P5 rim", "P6 release"]),
    ("finalize: bucketing + split check", ["F1 bucketing", "F2 split check"]),
    ("finalize: closure + assembly (blocks)", ["F3 sampled orientation", "F4 closing passes"]),
    ("finalize: join", ["F5 join"]),
    ("finalize: hand-over, checks, builder freed",
     ["F6 hand over stored form", "F7 shrink_to_fit", "F8 PlMap checks", "F9 builder release"]),
    ("folded-corner test + removal", ["Q1 folded test+removal"]),
    ("image measures", ["Q2 image measures"]),
    ("farther sheets", ["Q3 nearer sheet"]),
]
LINE = re.compile(r"TRACE (.+?) wall ([\d.]+) cpu ([\d.]+) thread ([\d.]+)")


def parse(path):
    phases, blocks = {}, []
    for line in open(path):
        m = LINE.match(line)
        if not m:
            continue
        name, wall, cpu, thread = m.group(1), *map(float, m.groups()[1:])
        if name.startswith("F4.block"):
            blocks.append(thread)
        else:
            phases[name] = (wall, cpu, thread)
    return phases, blocks


def runs(tags, case, threads):
    return [parse(f) for tag in tags for f in sorted(glob.glob(f"{tag}-{case}-{threads}-*.txt"))]


def one_thread(run, names):
    return sum(run[0].get(n, (0, 0, 0))[1] for n in names)


def critical_path(run, names):
    phases, blocks = run
    total = 0.0
    for n in names:
        if n not in phases:
            continue
        _, cpu, thread = phases[n]
        total += (max(blocks) if blocks else thread) if n == "F4 closing passes" else max(thread, cpu - thread)
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("before", nargs="+")
    ap.add_argument("--after", nargs="+", required=True)
    ap.add_argument("--changed", nargs="*", default=[], help="phase groups (prefix of the name) whose code differs")
    a = ap.parse_args()
    rows, t1, before, after = [], 0.0, 0.0, 0.0
    for group, names in GROUPS:
        changed = any(group.startswith(c) for c in a.changed)
        pool = a.before + a.after
        one = statistics.median([one_thread(r, names) for r in runs(pool, a.case, 1)])
        b_runs = runs(a.before if changed else pool, a.case, 2)
        f_runs = runs(a.after if changed else pool, a.case, 2)
        b = statistics.median([critical_path(r, names) for r in b_runs])
        f = statistics.median([critical_path(r, names) for r in f_runs])
        rows.append((group, one, b, f, f"{len(b_runs)} / {len(f_runs)}" if changed else f"{len(b_runs)} pooled"))
        t1, before, after = t1 + one, before + b, after + f
    print(f"| {a.case} | 1 thread: CPU s | share | 2 threads: critical path s, before | after | runs |")
    print("|---|---:|---:|---:|---:|---|")
    for group, one, b, f, n in rows:
        if max(one, b, f) >= 0.0005:
            print(f"| {group} | {one:.3f} | {100 * one / t1:.1f} % | {b:.3f} | {f:.3f} | {n} |")
    print(f"| **sum** | **{t1:.3f}** | | **{before:.3f}** | **{after:.3f}** | |")
    print(f"| **predicted speed-up** (one thread / path) | | | **{t1 / before:.2f}** | **{t1 / after:.2f}** | |")
    print(f"| serial share s | | | {100 * (2 * before / t1 - 1):.1f} % | {100 * (2 * after / t1 - 1):.1f} % | |")


if __name__ == "__main__":
    main()
