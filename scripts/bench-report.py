#!/usr/bin/env python3
"""Turn strata-bench --json files into Markdown tables and SVG plots.

    scripts/bench-report.py [--plots DIR] run1.json [run2.json ...]

Prints one set of tables per file, headed by the renderer and date the file
records: every case (strata, OpenCSG's best setting, the plain floor, their
ratios and OpenCSG's coverage agreement with strata), then every OpenCSG
setting's time. With --plots, also writes two log-log charts per scene and
image size with at least two K: frame time against K and memory against K
(strata, OpenCSG best, plain), as DIR/<scene>-<W>x<H>-time.svg and
-memory.svg. Only the standard library: the SVG is written by hand.
"""
import argparse
import json
import math
import os
import sys
from xml.sax.saxutils import escape


def mib(n):
    return n / (1024.0 * 1024.0)


def fmt(x):
    """Milliseconds with about three significant digits."""
    if x is None:
        return "–"
    if x >= 100:
        return f"{x:.0f}"
    if x >= 10:
        return f"{x:.1f}"
    return f"{x:.2f}"


def opencsg_best(r):
    o = r.get("opencsg", {})
    return o.get("best_ms"), o.get("best")


def ratio(a, b):
    if a is None or not b:
        return "–"
    q = a / b
    return f"{q:.2f}" if q < 10 else f"{q:.0f}"


def heading(run):
    ocsg = run.get("opencsg_renderer") or run.get("opencsg_unavailable", "OpenCSG not recorded")
    if run.get("opencsg_context"):
        ocsg += f" ({run['opencsg_context']})"
    return (
        f"#### {run['renderer']}, {run['gl_version']}; {ocsg}; {run['date']}\n\n"
        f"Median of {run['frames']} frames after {run['warmup']} warm-up, seed {run['seed']}, "
        f"OpenCSG settings capped at {run.get('opencsg_cap_ms', 0):.0f} ms a frame."
    )


def cases_table(run):
    lines = [
        "| scene | K | size | triangles | strata ms | OpenCSG ms (best setting) | plain ms | strata/OpenCSG "
        "| OpenCSG/plain | strata/plain | OpenCSG agrees | texture MiB | layers sum/max |",
        "| --- | ---: | --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |",
    ]
    for r in run["results"]:
        size = f"{r['width']}x{r['height']}"
        if "error" in r:
            lines.append(f"| {r['scene']} | {r['k']} | {size} | error: {r['error']} |" + " |" * 9)
            continue
        best_ms, best = opencsg_best(r)
        o = r.get("opencsg", {})
        best_row = next((s for s in o.get("settings", []) if s["name"] == best), {})
        capped = ", over the cap" if best_row.get("over_cap") else ""
        ocsg = f"{fmt(best_ms)} ({best}{capped})" if best else f"n/a ({o.get('unavailable', 'not run')})"
        agree = f"{100 * o['agreement_covered_away_from_edges']:.2f} %" if best else "–"
        lines.append(
            f"| {r['scene']} | {r['k']} | {size} | {r['triangles']} | {fmt(r['strata_ms'])} | {ocsg} | "
            f"{fmt(r['plain_ms'])} | {ratio(r['strata_ms'], best_ms)} | {ratio(best_ms, r['plain_ms'])} | "
            f"{ratio(r['strata_ms'], r['plain_ms'])} | {agree} | {mib(r['texture_bytes']):.0f} | "
            f"{r['layers_total']}/{r['layers_max']} |"
        )
    return "\n".join(lines)


def settings_table(run):
    names = []
    for r in run["results"]:
        for s in r.get("opencsg", {}).get("settings", []):
            if s["name"] not in names:
                names.append(s["name"])
    if not names:
        return ""
    lines = [
        "| scene | K | size | " + " | ".join(names) + " |",
        "| --- | ---: | --- |" + " ---: |" * len(names),
    ]
    notes = {}
    for r in run["results"]:
        settings = {s["name"]: s for s in r.get("opencsg", {}).get("settings", [])}
        if not settings:
            continue
        cells = []
        for n in names:
            s = settings.get(n)
            if s is None:
                cells.append("–")
            elif "skipped" in s:
                mark = notes.setdefault(s["skipped"], "*" * (len(notes) + 1))
                cells.append(f"skipped{mark}")
            else:
                cap = " (over cap)" if s.get("over_cap") else ""
                cells.append(f"{fmt(s['ms'])}{cap}")
        lines.append(f"| {r['scene']} | {r['k']} | {r['width']}x{r['height']} | " + " | ".join(cells) + " |")
    for why, mark in notes.items():
        lines.append(f"\n{mark} {why}")
    return "\n".join(lines)


# --- SVG charts -------------------------------------------------------------

W, H = 640, 420
LEFT, RIGHT, TOP, BOTTOM = 70, 20, 50, 60
COLORS = {"strata": "#1f77b4", "OpenCSG best": "#d62728", "plain": "#7f7f7f"}


def log_ticks(lo, hi):
    """1-2-5 ticks covering [lo, hi], fewer when the range is wide."""
    out = []
    e = math.floor(math.log10(lo))
    steps = (1, 2, 5) if math.log10(hi / lo) < 3 else (1,)
    while 10 ** e <= hi * 1.0001:
        for m in steps:
            v = m * 10 ** e
            if lo / 1.0001 <= v <= hi * 1.0001:
                out.append(v)
        e += 1
    return out


def label(v, unit):
    if unit == "MiB" and v < 1:
        return f"{v:g}"
    return f"{v:g}" if v < 1e6 else f"{v:.0e}"


def chart(title, subtitle, ylabel, unit, series):
    """series: {name: [(k, value), ...]}; log-log axes, one line and marker per series."""
    points = [(k, v) for pts in series.values() for k, v in pts if v and v > 0]
    if not points:
        return None
    ks = sorted({k for k, _ in points})
    xlo, xhi = min(ks), max(ks)
    if xlo == xhi:
        xlo, xhi = xlo / 2, xhi * 2
    ylo = 10 ** math.floor(math.log10(min(v for _, v in points)))
    yhi = 10 ** math.ceil(math.log10(max(v for _, v in points)))
    if ylo == yhi:
        yhi *= 10

    def x(k):
        return LEFT + (W - LEFT - RIGHT) * (math.log(k) - math.log(xlo)) / (math.log(xhi) - math.log(xlo))

    def y(v):
        return H - BOTTOM - (H - TOP - BOTTOM) * (math.log(v) - math.log(ylo)) / (math.log(yhi) - math.log(ylo))

    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" '
        'font-family="sans-serif" font-size="12">',
        f'<rect width="{W}" height="{H}" fill="white"/>',
        f'<text x="{W / 2}" y="20" text-anchor="middle" font-size="15">{escape(title)}</text>',
        f'<text x="{W / 2}" y="37" text-anchor="middle" font-size="11" fill="#555">{escape(subtitle)}</text>',
    ]
    for v in log_ticks(ylo, yhi):
        out.append(f'<line x1="{LEFT}" x2="{W - RIGHT}" y1="{y(v):.1f}" y2="{y(v):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{LEFT - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{label(v, unit)}</text>')
    for k in ks:
        out.append(f'<line x1="{x(k):.1f}" x2="{x(k):.1f}" y1="{TOP}" y2="{H - BOTTOM}" stroke="#eee"/>')
        out.append(f'<text x="{x(k):.1f}" y="{H - BOTTOM + 16}" text-anchor="middle">{k}</text>')
    out.append(f'<rect x="{LEFT}" y="{TOP}" width="{W - LEFT - RIGHT}" height="{H - TOP - BOTTOM}" '
               'fill="none" stroke="black"/>')
    out.append(f'<text x="{(LEFT + W - RIGHT) / 2}" y="{H - 18}" text-anchor="middle">K (operands cut or intersected)</text>')
    out.append(f'<text transform="translate(18 {(TOP + H - BOTTOM) / 2}) rotate(-90)" text-anchor="middle">'
               f'{escape(ylabel)}</text>')
    for i, (name, pts) in enumerate(series.items()):
        color = COLORS.get(name, "#2ca02c")
        pts = [(k, v) for k, v in sorted(pts) if v and v > 0]
        if len(pts) > 1:
            path = " ".join(f"{x(k):.1f},{y(v):.1f}" for k, v in pts)
            out.append(f'<polyline points="{path}" fill="none" stroke="{color}" stroke-width="2"/>')
        for k, v in pts:
            out.append(f'<circle cx="{x(k):.1f}" cy="{y(v):.1f}" r="3.5" fill="{color}"/>')
        ly = TOP + 16 + 18 * i
        out.append(f'<line x1="{LEFT + 12}" x2="{LEFT + 36}" y1="{ly - 4}" y2="{ly - 4}" stroke="{color}" stroke-width="2"/>')
        out.append(f'<text x="{LEFT + 42}" y="{ly}">{escape(name)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def plots(run, directory):
    groups = {}
    for r in run["results"]:
        if "error" not in r:
            groups.setdefault((r["scene"], r["width"], r["height"]), []).append(r)
    written = []
    machine = f"{run['renderer']}, {run['date']}"
    for (scene, w, h), rows in sorted(groups.items()):
        if len({r["k"] for r in rows}) < 2:
            continue
        name = f"{scene}-{w}x{h}"
        time = {
            "strata": [(r["k"], r["strata_ms"]) for r in rows],
            "OpenCSG best": [(r["k"], opencsg_best(r)[0]) for r in rows],
            "plain": [(r["k"], r["plain_ms"]) for r in rows],
        }
        memory = {
            "strata": [(r["k"], mib(r["texture_bytes"])) for r in rows],
            "OpenCSG best": [(r["k"], mib(r.get("opencsg", {}).get("buffer_bytes", 0))) for r in rows],
            "plain": [(r["k"], mib(r.get("plain_bytes", 0))) for r in rows],
        }
        for kind, series, ylabel, unit, what in (
            ("time", time, "frame time, ms (log)", "ms", "frame time"),
            ("memory", memory, "GPU memory, MiB (log)", "MiB",
             "memory (strata: layered textures; others: buffers)"),
        ):
            svg = chart(f"{scene} {w}x{h}: {what} against K", machine, ylabel, unit, series)
            if svg is None:
                continue
            path = os.path.join(directory, f"{name}-{kind}.svg")
            with open(path, "w", encoding="utf-8") as f:
                f.write(svg)
            written.append(path)
    return written


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument("--plots", metavar="DIR", help="also write SVG charts into DIR")
    parser.add_argument("files", nargs="+", metavar="run.json")
    args = parser.parse_args(argv)
    for i, path in enumerate(args.files):
        try:
            with open(path, encoding="utf-8") as f:
                run = json.load(f)
        except (OSError, ValueError) as e:
            print(f"{path}: {e}", file=sys.stderr)
            return 1
        if i:
            print()
        print(heading(run))
        print()
        print(cases_table(run))
        settings = settings_table(run)
        if settings:
            print()
            print("OpenCSG, every setting (ms; oq: occlusion queries, dcs: depth complexity sampling):")
            print()
            print(settings)
        if args.plots:
            os.makedirs(args.plots, exist_ok=True)
            for written in plots(run, args.plots):
                print(f"wrote {written}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
