#!/usr/bin/env python3
"""Turn strata-bench --json files into the Markdown tables of docs/benchmarks.md.

    scripts/bench-report.py run1.json [run2.json ...]

One table per file, headed by the renderer and date the file records. Only the
standard library; no plots yet.
"""
import json
import sys


def mib(n):
    return n / (1024.0 * 1024.0)


def table(run):
    lines = [
        f"#### {run['renderer']}, {run['date']} "
        f"(median of {run['frames']} frames after {run['warmup']} warm-up, seed {run['seed']})",
        "",
        "| scene | K | size | triangles | strata ms | plain ms | strata/plain | peel ms | evaluate ms | shade ms | texture MiB | layers sum/max | covered px |",
        "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: |",
    ]
    for r in run["results"]:
        size = f"{r['width']}x{r['height']}"
        if "error" in r:
            lines.append(f"| {r['scene']} | {r['k']} | {size} | error: {r['error']} |" + " |" * 9)
            continue
        ratio = r["strata_ms"] / r["plain_ms"] if r["plain_ms"] > 0 else float("nan")
        lines.append(
            f"| {r['scene']} | {r['k']} | {size} | {r['triangles']} | {r['strata_ms']:.1f} | "
            f"{r['plain_ms']:.2f} | {ratio:.1f} | {r['peel_ms']:.1f} | {r['evaluate_ms']:.1f} | "
            f"{r['shade_ms']:.1f} | {mib(r['texture_bytes']):.0f} | "
            f"{r['layers_total']}/{r['layers_max']} | {r['covered_pixels']} |"
        )
    return "\n".join(lines)


def main(paths):
    if not paths:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    for i, path in enumerate(paths):
        try:
            with open(path, encoding="utf-8") as f:
                run = json.load(f)
        except (OSError, ValueError) as e:
            print(f"{path}: {e}", file=sys.stderr)
            return 1
        if i:
            print()
        print(table(run))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
