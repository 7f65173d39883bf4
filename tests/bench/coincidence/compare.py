#!/usr/bin/env python3
"""Frame and evaluator times of two builds, from strata-bench --json files.

    tests/bench/coincidence/compare.py [--control] [DIR]

DIR (default: results/runs/coincidence of this repository) holds
strata-bench --json files named old-<part>-run<N>.json and
new-<part>-run<N>.json: the same command run by the build before the
coincidence rule (old) and by the build with it (new), interleaved: old run
1, new run 1, old run 2... (results/log.md, "what the coincidence rule
costs, two builds"). Prints one Markdown row per scene, K and size:
the median over the runs of strata ms and of evaluate ms for each build,
and new/old as the median of the run-by-run ratios (new run N over old run
N, seconds apart), from which the host's slower swings of load cancel out.
With --control, the same run-by-run medians instead for the other passes
(normal, shade, the plain draw, and the peel, which the rule touches only
where a scene has groups of convex operands): how far from 1.00 noise alone
moves a ratio, and what the groups' tie passes cost. Only the standard library.
"""
import json
import os
import re
import statistics
import sys

PART_ORDER = ["cheese", "scenes", "files"]


def load(directory):
    """{(part, scene, k, size): {build: {run: result}}}, cheese, scenes, files."""
    cases = {}
    pattern = re.compile(r"^(old|new)-(\w+)-run(\d+)\.json$")
    found = []
    for name in os.listdir(directory):
        m = pattern.match(name)
        if m and m.group(2) in PART_ORDER:
            found.append((PART_ORDER.index(m.group(2)), int(m.group(3)), m.group(1), m.group(2), name))
    for _, run, build, part, name in sorted(found):
        with open(os.path.join(directory, name)) as f:
            for r in json.load(f)["results"]:
                if "error" in r:
                    continue
                key = (part, r["scene"], r["k"], f'{r["width"]}x{r["height"]}')
                cases.setdefault(key, {"old": {}, "new": {}})[build][run] = r
    return cases


def fmt(x):
    """Milliseconds with about three significant digits."""
    if x >= 100:
        return f"{x:.0f}"
    if x >= 10:
        return f"{x:.1f}"
    return f"{x:.2f}"


def median(runs, field):
    return statistics.median(r[field] for r in runs.values())


def paired(old, new, field):
    """Median over the runs of new run N / old run N."""
    return statistics.median(new[n][field] / old[n][field] for n in old if n in new and old[n][field] > 0)


def main():
    args = [a for a in sys.argv[1:] if a != "--control"]
    control = "--control" in sys.argv[1:]
    here = os.path.dirname(os.path.abspath(__file__))
    directory = args[0] if args else os.path.join(here, "..", "..", "..", "results", "runs", "coincidence")
    cases = load(directory)
    if not cases:
        sys.exit(f"no old-*-runN.json / new-*-runN.json files in {directory}")
    if control:
        print("| scene | K | size | peel new/old | normal new/old | shade new/old | plain new/old |")
        print("| --- | ---: | --- | ---: | ---: | ---: | ---: |")
    else:
        print("| scene | K | size | old strata ms | new strata ms | new/old "
              "| old evaluate ms | new evaluate ms | new/old |")
        print("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for (part, scene, k, size), c in sorted(cases.items(), key=lambda kv: PART_ORDER.index(kv[0][0])):
        old, new = c["old"], c["new"]
        if not old or not new:
            continue
        name = f"`{scene}`" if part == "files" else scene
        if control:
            ratios = " | ".join(f"{paired(old, new, f):.2f}" for f in ("peel_ms", "normal_ms", "shade_ms", "plain_ms"))
            print(f"| {name} | {k} | {size} | {ratios} |")
            continue
        print(f"| {name} | {k} | {size} | {fmt(median(old, 'strata_ms'))} | {fmt(median(new, 'strata_ms'))} "
              f"| {paired(old, new, 'strata_ms'):.2f} | {fmt(median(old, 'evaluate_ms'))} "
              f"| {fmt(median(new, 'evaluate_ms'))} | {paired(old, new, 'evaluate_ms'):.2f} |")


if __name__ == "__main__":
    main()
