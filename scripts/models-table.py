#!/usr/bin/env python3
"""Join the two halves of scripts/bench-models.sh into one Markdown table.

    scripts/models-table.py first-image.md frames.json

first-image.md is scripts/bench-first-image.sh's table (whole processes,
strata-render against OpenSCAD's preview); frames.json is strata-bench
--json of the same models (steady frames, strata against OpenCSG as
OpenSCAD's preview draws). One row per model, in the first file's order,
then a line of how many models meet each target of docs/benchmarks.md.
A model strata drew as a plain frame (a union seen from outside) has
"(plain)" beside its ratio to the plain draw of the same triangles.
"""
import json
import re
import sys

sys.path.insert(0, __import__("os").path.dirname(__file__))
from importlib import import_module

fmt = import_module("bench-report").fmt


def first_images(path):
    rows = {}
    for line in open(path):
        m = re.match(r"\| `([^`]+)` \| ([\d.]+|fail) \| ([\d.]+|fail) \| [\d.]+ \| (\d+|fail) \| (\d+|fail) \|", line)
        if m:
            name, st, ot, sm, om = m.groups()
            num = lambda v: None if v == "fail" else float(v)
            rows[name] = (num(st), num(ot), num(sm), num(om))
    return rows


def ratio(a, b):
    return a / b if a is not None and b else None


def cell(v, digits=2):
    return "–" if v is None else f"{v:.{digits}f}"


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__.strip().splitlines()[2].strip())
    images = first_images(argv[1])
    run = json.load(open(argv[2]))
    frames = {r["scene"]: r for r in run["results"]}
    print("| model | leaves | first image: strata s | OpenSCAD s | ratio | strata MiB | OpenSCAD MiB | ratio |"
          " frame: strata ms | OpenCSG ms | ratio | plain draw ms | ratio |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    met = {"time": 0, "memory": 0, "frame": 0, "plain": 0}
    counted = {"time": 0, "memory": 0, "frame": 0, "plain": 0}
    for name, (st, ot, sm, om) in images.items():
        r = frames.get(name, {})
        k = r.get("k")
        sf = r.get("strata_ms")
        of = r.get("opencsg", {}).get("best_ms")
        pf = r.get("plain_ms")
        plain = r.get("plain_frame", False)
        tr, mr, fr, pr = ratio(st, ot), ratio(sm, om), ratio(sf, of), ratio(sf, pf)
        if plain and pr is not None:
            counted["plain"] += 1
            met["plain"] += pr <= 1.5
        if tr is not None:
            counted["time"] += 1
            met["time"] += tr <= 1.0
        if mr is not None:
            counted["memory"] += 1
            met["memory"] += mr <= 1.5
        if fr is not None and k is not None:
            counted["frame"] += 1
            met["frame"] += fr <= (0.5 if k >= 16 else 1.0)
        # A frame drawn plainly (a union seen from outside) is marked with its ratio to the plain draw.
        print(f"| `{name}` | {k if k is not None else '–'} | {cell(st)} | {cell(ot)} | {cell(tr)} |"
              f" {cell(sm, 0)} | {cell(om, 0)} | {cell(mr)} | {fmt(sf)} | {fmt(of)} | {cell(fr)} |"
              f" {fmt(pf)} | {cell(pr) + (' (plain)' if plain else '')} |")
    print()
    print(f"First image at most OpenSCAD's: {met['time']} of {counted['time']}; peak memory at most 1.5 times"
          f" OpenSCAD's: {met['memory']} of {counted['memory']}; steady frame at most 0.5 times OpenCSG's"
          f" (from 16 leaves; at most 1 times below): {met['frame']} of {counted['frame']}; drawn plainly at most"
          f" 1.5 times the plain draw: {met['plain']} of {counted['plain']}.")


if __name__ == "__main__":
    main(sys.argv)
