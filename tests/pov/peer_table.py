"""The table a comparison with another renderer ends with (convert_viewer.py,
integrator_vs_povray.py): what was run on which machine at what load, then a row per scene,
written to a Markdown file and printed; with --check, exit status 1 when a scene missed."""

import os
import platform
import time


def machine(load_before):
    """The machine, its load before and now, and the time: times are read against these."""
    return (f"{platform.node()}, {os.cpu_count()} cores, load average {load_before:.1f} before, "
            f"{os.getloadavg()[0]:.1f} after; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")


def report(path, heading, columns, rows, missed, check, footer=()):
    """Writes and prints the table; returns the exit status."""
    table = [heading, "", "| " + " | ".join(columns) + " |", "|" + "---|" * len(columns), *rows,
             *footer]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(table) + "\n", encoding="utf-8")
    print("\n".join(table))
    if check and missed:
        print("missed: " + ", ".join(missed))
        return 1
    return 0
