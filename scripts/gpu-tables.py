#!/usr/bin/env python3
"""The GPU tables of a gpu-bench.sh run, as results/log.md keeps them.

    scripts/gpu-tables.py DIR

DIR holds bench-synthetic.json, bench-files.json and first-image.json as
scripts/gpu-bench.sh writes them. Prints three Markdown tables: the seeded
scenes, the models' frames, and the whole-process first images.
"""
import importlib.util
import json
import os
import sys


def load_report():
    """scripts/bench-report.py, for its number format (its name is no module name)."""
    spec = importlib.util.spec_from_file_location("bench_report", os.path.join(os.path.dirname(__file__),
                                                                                "bench-report.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


number = load_report().fmt  # about three significant digits, as every table of benchmarks.md


def frames(results, first_column):
    print(f"| {first_column} | {'K' if first_column == 'scene' else 'leaves'} | size | strata ms | plain ms | "
          "strata / plain | peel ms | evaluate ms | normal ms | shade ms | texture MiB |")
    print("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in results:
        if r.get("strata_ms") is None:
            continue
        ratio = r["strata_ms"] / r["plain_ms"] if r.get("plain_ms") else None
        print(f"| {r['scene']} | {r['k']} | {r['width']}x{r['height']} | {number(r['strata_ms'])} | "
              f"{number(r.get('plain_ms'))} | {number(ratio)} | {number(r['peel_ms'])} | {number(r['evaluate_ms'])} | "
              f"{number(r['normal_ms'])} | {number(r['shade_ms'])} | {r['texture_bytes'] / 2**20:.0f} |")


def first_images(data):
    print("| model | median s | first s (empty shader cache) | peak MiB | in-process total ms | context ms | "
          "geometry ms | first frame ms |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for m in data["models"]:
        stats = m.get("stats_last") or {}
        t = stats.get("time_ms", {})
        rss = max(m.get("max_rss_kib") or [0]) / 1024
        print(f"| `{os.path.basename(m['model'])}` | {m['median_s']:.3f} | {m['first_s']:.3f} | {rss:.0f} | "
              f"{t.get('total', 0):.0f} | {t.get('context', 0):.0f} | {t.get('geometry', 0):.0f} | "
              f"{t.get('frame', 0):.0f} |")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: scripts/gpu-tables.py DIR")
    folder = sys.argv[1]
    with open(os.path.join(folder, "bench-synthetic.json")) as f:
        frames(json.load(f)["results"], "scene")
    print()
    with open(os.path.join(folder, "bench-files.json")) as f:
        frames(json.load(f)["results"], "model")
    print()
    with open(os.path.join(folder, "first-image.json")) as f:
        first_images(json.load(f))


if __name__ == "__main__":
    main()
