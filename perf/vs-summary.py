#!/usr/bin/env python3
"""Lantern's best run against each peer's best, from perf/vs-renderers.sh's
table (standard input or a file): per scene and time, the least relMSE and
the least MSE among Lantern's rows, over the least among pbrt-v4's and
among Cycles' rows. Prints a Markdown table; a ratio under 0.5 meets the
goal of half the peer's error.

Errors against the references are used where the table has them, the
pairs' (PAIRS=1) where it has only those, or everywhere with --pairs. A
pair sees no reference's noise, but it caps a rare bright sample: against
the pair's mean a pixel's relative error is at most about 2, where against
a converged image a caustic a path tracer found once counts in full.
--robust takes relMSE from the robust column instead (against the
references, without the 0.01% of pixels whose error is largest; MSE is
unchanged). Columns are found by their headers, so tables of earlier
versions of the script, without the robust column, read as before.

    python3 perf/vs-summary.py [--pairs | --robust] /tmp/vs.txt
"""
import sys


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def cells_of(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def read_rows(lines, prefer):
    rows, column = [], {}
    for line in lines:
        cells = cells_of(line)
        if cells[0] == "scene":
            column = {name: k for k, name in enumerate(cells)}
            continue
        if len(cells) < 6 or not column or cells[0] == "" or cells[0].startswith("---"):
            continue

        def at(name):
            k = column.get(name)
            return number(cells[k]) if k is not None and k < len(cells) else None

        rel, mse = at("relMSE"), at("MSE")
        pair_rel, pair_mse = at("relMSE, seeds 7 and 8"), at("MSE, seeds 7 and 8")
        if pair_rel is not None and (prefer == "pairs" or rel is None):
            rel, mse = pair_rel, pair_mse
        elif prefer == "robust" and at("robust relMSE") is not None:
            rel = at("robust relMSE")
        if rel is None or mse is None:
            continue  # a failed run
        renderer = cells[1]
        peer = "Lantern" if renderer.startswith("Lantern") else "pbrt-v4" if renderer.startswith("pbrt-v4") else "Cycles"
        rows.append((cells[0], cells[2] if peer != "pbrt-v4" else None, peer, renderer, rel, mse))
    return rows


def main():
    args = sys.argv[1:]
    prefer = "pairs" if "--pairs" in args else "robust" if "--robust" in args else None
    args = [a for a in args if a not in ("--pairs", "--robust")]
    lines = open(args[0]).readlines() if args else sys.stdin.readlines()
    rows = read_rows(lines, prefer)
    # pbrt-v4's time column says what it took; its errors are already
    # scaled to the budget: it belongs to the Lantern rows' budget before it.
    budget, groups = None, {}
    for scene, t, peer, renderer, rel, mse in rows:
        if t is not None:
            budget = t
        groups.setdefault((scene, budget), {}).setdefault(peer, []).append((renderer, rel, mse))
    print("| scene | time (s) | Lantern's least relMSE (run) | / pbrt-v4's | / Cycles' "
          "| Lantern's least MSE (run) | / pbrt-v4's | / Cycles' |")
    print("|---|---|---|---|---|---|---|---|")
    for (scene, t), peers in groups.items():
        if "Lantern" not in peers:
            continue
        out = [scene, t]
        for k in (1, 2):
            run, best = min(((r[0], r[k]) for r in peers["Lantern"]), key=lambda x: x[1])
            out.append("%.3g (%s)" % (best, run.replace("Lantern ", "")))
            for peer in ("pbrt-v4", "Cycles"):
                theirs = min((r[k] for r in peers.get(peer, [])), default=None)
                out.append("%.2g" % (best / theirs) if theirs else "")
        print("| " + " | ".join(out) + " |")


main()
