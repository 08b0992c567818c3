#!/usr/bin/env python3
"""Medians of the peer projection benchmark (run.sh): reads raw.jsonl, writes summary.jsonl and
a Markdown table. Usage: summarize.py RAW SUMMARY TABLE [RUN_INFO]. Standard library only."""
import json
import statistics
import sys
from collections import OrderedDict

TOOL_NAMES = {"plmap": "plmap", "contactmerge": "ContactMerge", "psurface": "PSurface"}


def load(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def summarize(runs):
    groups = OrderedDict()
    for r in runs:
        key = (r.get("family"), r.get("size"), r.get("tool"), r.get("threads", 1))
        groups.setdefault(key, []).append(r)
    # Sizes per case, for the tools whose process died before printing them.
    sizes = {}
    for r in runs:
        if "label" in r:
            sizes[(r.get("family"), r.get("size"))] = (r["s1_cells"], r["s2_cells"])
    out = []
    for (family, size, tool, threads), rs in groups.items():
        ok = [r for r in rs if r.get("ok")]
        s = {"family": family, "size": size, "tool": tool, "threads": threads, "runs": len(rs),
             "ok_runs": len(ok)}
        if (family, size) in sizes:
            s["s1_cells"], s["s2_cells"] = sizes[(family, size)]
        if ok:
            s["seconds"] = statistics.median(r["seconds"] for r in ok)
            s["seconds_all"] = [r["seconds"] for r in ok]
            s["peak_increase_mib"] = statistics.median(r["peak_increase_mib"] for r in ok)
            first = ok[0]
            for k in ("covered", "exact_overlap", "covered_relative_error", "covered_target",
                      "exact_target_overlap", "covered_target_relative_error", "pieces"):
                s[k] = first.get(k)
            if tool == "plmap":
                d = first.get("details", {})
                s["edges_not_inserted"] = d.get("edges_not_inserted")
                s["finalize_seconds"] = statistics.median(
                    r["details"]["seconds_by_phase"]["finalize"] for r in ok)
        else:
            s["error"] = rs[0].get("error", "")
        out.append(s)
    return out


def case_name(family, size):
    if family == "sphere":
        return f"sphere L{size}"
    if family == "femur":
        return "femur remeshed"
    return family


def fmt_time(s):
    if "seconds" not in s:
        return "—"
    t = s["seconds"]
    return f"{t:.3g}" if t < 100 else f"{t:.0f}"


def fmt_err(x):
    if x is None:
        return "—"
    return "0" if abs(x) < 5e-16 else f"{x:+.1e}"


def short_error(s):
    e = s.get("error", "")
    return (e[:70] + "…") if len(e) > 70 else e


def table(summary, info):
    lines = []
    if info:
        lines += ["```", info.strip(), "```", ""]
    lines += [
        "Time: wall seconds of the projection alone (median of the runs; input generation and "
        "conversion excluded). Memory: peak resident memory during the projection minus the "
        "resident memory just before it (MiB, median). Covered error: (covered − exact) / exact "
        "on S1 and on S2; exact overlap known analytically (planes: 0.72; closed pairs: the whole "
        "surface). plmap 'all' = all cores (2 here).",
        "",
        "| case | S1 × S2 | tool | threads | time [s] | peak +MiB | covered err S1 | covered err S2 | pieces | note |",
        "|---|---|---|---|---:|---:|---:|---:|---:|---|",
    ]
    for s in summary:
        name = TOOL_NAMES.get(s["tool"], s["tool"])
        threads = "all" if s["tool"] == "plmap" and s["threads"] == 0 else "1"
        dims = f'{s.get("s1_cells", "?")} × {s.get("s2_cells", "?")}'
        note = ""
        if s.get("ok_runs", 0) == 0:
            note = "FAILED: " + short_error(s)
        elif s["tool"] == "plmap" and s.get("edges_not_inserted"):
            note = f'{s["edges_not_inserted"]} S2 edges not inserted'
        if s.get("ok_runs", 0) and s["ok_runs"] < s["runs"]:
            note += f' ({s["runs"] - s["ok_runs"]} of {s["runs"]} runs failed)'
        mem = f'{s["peak_increase_mib"]:.1f}' if "peak_increase_mib" in s else "—"
        lines.append(
            f'| {case_name(s["family"], s["size"])} | {dims} | {name} | {threads} | {fmt_time(s)} | {mem} | '
            f'{fmt_err(s.get("covered_relative_error"))} | {fmt_err(s.get("covered_target_relative_error"))} | '
            f'{s.get("pieces", "—") if s.get("ok_runs") else "—"} | {note} |')

    # Ratios plmap / peer, per case, when both succeeded.
    by_case = OrderedDict()
    for s in summary:
        by_case.setdefault((s["family"], s["size"]), {})[(s["tool"], s["threads"])] = s
    lines += ["", "Ratios plmap / peer (below 1: plmap faster or smaller). 1t = plmap on one thread, "
              "all = plmap on all cores; peers on one thread.", "",
              "| case | S1 × S2 | peer | time 1t | time all | memory 1t |", "|---|---|---|---:|---:|---:|"]
    for (family, size), tools in by_case.items():
        p1 = tools.get(("plmap", 1))
        any_tool = next(iter(tools.values()))
        dims = f'{any_tool.get("s1_cells", "?")} × {any_tool.get("s2_cells", "?")}'
        pall = tools.get(("plmap", 0))
        for peer in ("contactmerge", "psurface"):
            q = tools.get((peer, 1))
            if not q or "seconds" not in q:
                continue
            def ratio(a, key):
                if not a or key not in a or not q.get(key):
                    return "—"
                return f"{a[key] / q[key]:.3g}"
            lines.append(f"| {case_name(family, size)} | {dims} | {TOOL_NAMES[peer]} | {ratio(p1, 'seconds')} | "
                         f"{ratio(pall, 'seconds')} | {ratio(p1, 'peak_increase_mib')} |")
    return "\n".join(lines) + "\n"


def main():
    raw, summary_path, table_path = sys.argv[1:4]
    info = open(sys.argv[4]).read() if len(sys.argv) > 4 else ""
    summary = summarize(load(raw))
    with open(summary_path, "w") as f:
        for s in summary:
            f.write(json.dumps(s) + "\n")
    with open(table_path, "w") as f:
        f.write(table(summary, info))


if __name__ == "__main__":
    main()
