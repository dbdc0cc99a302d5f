#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The Markdown tables of docs/boards.md, "Real time", from a tick_budget.py report:

    tick_budget_tables.py benchmarks/qemu/results/tick_budget.json

prints the summary (one row per image: its verdict) and the per-job table."""
import json
import sys


def k(value):
    """Instructions in thousands or millions, as the tables show them."""
    return f"{value / 1e6:.2f} M" if value >= 1e6 else f"{value / 1e3:.1f} k"


def span(values, fmt):
    low, high = min(values), max(values)
    return fmt(low) if fmt(low) == fmt(high) else f"{fmt(low)}-{fmt(high)}"


def summary(report):
    lines = ["| board | image | meets the budget | jobs within | worst tick | mean tick | p99 tick (at most) | "
             "worst tick / period (CPI 1.0-1.3) | per segment or piece | needed per s (max) | possible per s (min, CPI 1.3) |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for v in report["images"]:
        rows = [r for r in report["results"] if r["image_target"] == v["image_target"] and r["elf"] == v["elf"]
                and "error" not in r]
        if not rows:
            lines.append(f"| {v['board']} | {v['image']} | no | 0/{v['jobs']} | | | | | | | |")
            continue
        share = [r["budget"]["worst_tick_share_of_period"] for r in rows]
        worst = max(rows, key=lambda r: r["instructions_per_tick"]["worst"])
        lines.append(
            f"| {v['board']} | {v['image']} | **{'yes' if v['meets_budget'] else 'no'}** | "
            f"{v['jobs_within_budget']}/{v['jobs']} | {k(worst['instructions_per_tick']['worst'])} | "
            f"{span([r['instructions_per_tick']['mean'] for r in rows], k)} | "
            f"{k(max(r['instructions_per_tick']['p99_at_most'] for r in rows))} | "
            f"{max(s[0] for s in share):.0%}-{max(s[1] for s in share):.0%} | "
            f"{span([r['instructions_per_segment']['total_mean'] for r in rows], k)} | "
            f"{max(r['budget']['segments_per_s_needed'] for r in rows):.1f} | "
            f"{min(r['budget']['segments_per_s_possible'] for r in rows):.1f} |")
    return "\n".join(lines)


def per_job(report):
    lines = ["| board | image | job | worst | mean | p99 | segments | per segment | worst/period CPI 1.3 | "
             "needed / possible per s | within |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in report["results"]:
        if "error" in r:
            lines.append(f"| {r['board']} | {r['image']} | {r['job']} | | | | | | | | run failed: {' '.join(r['error'].split())[-80:]} |")
            continue
        t, b = r["instructions_per_tick"], r["budget"]
        lines.append(f"| {r['board']} | {r['image']} | {r['job']} | {t['worst']} | {t['mean']:.0f} | {t['p99_at_most']} | "
                     f"{r['segments']} | {r['instructions_per_segment']['total_mean']} | "
                     f"{b['worst_tick_share_of_period'][1]:.0%} | {b['segments_per_s_needed']} / "
                     f"{b['segments_per_s_possible']} | {'yes' if r['within_budget'] else 'no'} |")
    return "\n".join(lines)


def main():
    with open(sys.argv[1], encoding="utf-8") as handle:
        report = json.load(handle)
    print(summary(report))
    print()
    print(per_job(report))
    return 0


if __name__ == "__main__":
    sys.exit(main())
