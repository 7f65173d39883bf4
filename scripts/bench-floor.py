#!/usr/bin/env python3
"""Compare strata-bench runs of the engine with runs of stand-in shaders.

    scripts/bench-floor.py DIR

DIR holds strata-bench --json files named engine-<anything>-run<N>.json and
stand-in-<anything>-run<N>.json (the same command, the second run with
STRATA_SHADER_DIR=tests/bench/lower-bound/stand-in-shaders; see
benchmarks.md, "The pipeline's lower bound on llvmpipe"). Prints one
Markdown row per scene, K and size: strata/OpenCSG of each engine run,
strata/OpenCSG and strata/plain of each stand-in run, and the range of
OpenCSG/plain over all of them. Every ratio is taken within one run
(one process, one row), never across runs: the host's load moves between
runs by more than the ratios do.
"""
import collections
import glob
import json
import os
import re
import sys

SCENE_ORDER = ["cheese", "stack", "intersection", "deep", "tori", "mesh"]


def load(directory):
    """{(scene, k, size): {kind: [(run, strata, plain, opencsg best)]}}"""
    rows = collections.defaultdict(lambda: collections.defaultdict(list))
    pattern = re.compile(r"^(engine|stand-in)-.*-run(\d+)\.json$")
    for path in sorted(glob.glob(os.path.join(directory, "*.json"))):
        match = pattern.match(os.path.basename(path))
        if not match:
            continue
        kind, run = match.group(1), int(match.group(2))
        with open(path) as f:
            for r in json.load(f)["results"]:
                opencsg = r.get("opencsg")
                best = opencsg.get("best_ms") if isinstance(opencsg, dict) else None
                if not best or not r.get("plain_ms"):
                    continue
                key = (r["scene"], r["k"], f"{r['width']}x{r['height']}")
                rows[key][kind].append((run, r["strata_ms"], r["plain_ms"], best))
    return rows


def ratios(values):
    return ", ".join(f"{v:.2f}" for v in values)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    rows = load(sys.argv[1])
    if not rows:
        sys.exit(f"{sys.argv[1]}: no engine-*-runN.json or stand-in-*-runN.json files with OpenCSG figures")
    print("| scene | K | size | strata/OpenCSG, engine | strata/OpenCSG, stand-ins | strata/plain, stand-ins | OpenCSG/plain |")
    print("| --- | ---: | --- | --- | --- | --- | --- |")
    order = {name: i for i, name in enumerate(SCENE_ORDER)}
    for key in sorted(rows, key=lambda k: (order.get(k[0], len(order)), k[0], k[1], k[2])):
        runs = {kind: sorted(rows[key][kind]) for kind in ("engine", "stand-in")}
        engine = [s / o for _, s, _, o in runs["engine"]]
        stand_in = [s / o for _, s, _, o in runs["stand-in"]]
        stand_in_plain = [s / p for _, s, p, _ in runs["stand-in"]]
        opencsg_plain = [o / p for kind in runs for _, _, p, o in runs[kind]]
        print(f"| {key[0]} | {key[1]} | {key[2]} | {ratios(engine)} | {ratios(stand_in)} | "
              f"{ratios(stand_in_plain)} | {min(opencsg_plain):.1f}–{max(opencsg_plain):.1f} |")


if __name__ == "__main__":
    main()
