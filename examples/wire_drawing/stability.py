#!/usr/bin/python3
"""Tabulate the wire drawing stability runs (stability.sh): how each ended, iterations per step
and the message of a run that stopped.

    stability.py [results/stability]
"""
import pathlib
import sys

from cocopp.results import read_summary, results_path

HERE = pathlib.Path(__file__).resolve().parent


def main():
    folder = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else HERE / "results" / "stability")
    rows = ["| variant | status | steps | iterations per step (max) | wall time | message |",
            "|---|---|---|---|---|---|"]
    for case_file in sorted(folder.glob("*/case.yaml")):
        s = read_summary(results_path(case_file), missing_ok=True)
        if not s:
            continue  # not run, or still running
        name = case_file.parent.name
        per_step = s.get("iterations_per_step", [])
        iterations = (f"{sum(per_step) / len(per_step):.2f} ({max(per_step)})" if per_step else "-")
        message = (s.get("message") or "").splitlines()
        rows.append(f"| {name} | {s.get('status', '?')} | {s.get('last_step') or 0} / "
                    f"{s.get('number_of_timesteps', '?')} | {iterations} | "
                    f"{s.get('wall_time', 0):.0f} s | {message[0] if message else ''} |")
    table = "\n".join(rows)
    print(table)
    (folder / "stability.md").write_text(table + "\n")


if __name__ == "__main__":
    main()
