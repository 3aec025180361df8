#!/usr/bin/env python3
"""Checks a finished tissuefem study directory (ctest studies/*).

usage: check_study.py DIR SERIES=ORDER [SERIES=ORDER ...] [--tolerance TOL]

- every variant finished;
- the last observed order of each named series in rates.csv is within 0.1 of
  the theoretical ORDER;
- both charts exist and are non-empty PNG files;
- with --tolerance: the variant named in choice.txt is, recomputed here from
  results.csv, the one the picker's rule gives (error <= TOL, least wall time
  of the steps per simulated time unit).
Prints one line per check; exits 1 on the first failure.
"""
import csv
import os
import re
import sys


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)


def main():
    args = sys.argv[1:]
    directory = args.pop(0)
    tolerance = None
    if "--tolerance" in args:
        i = args.index("--tolerance")
        tolerance = float(args[i + 1])
        del args[i:i + 2]
    with open(os.path.join(directory, "results.csv")) as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    status = header.index("status")
    for r in rows:
        if r[status] != "finished":
            fail("variant %s: %s" % (r[0], r[status]))
    print("all %d variants finished" % len(rows))

    with open(os.path.join(directory, "rates.csv")) as f:
        rates = list(csv.reader(f))[1:]
    for expectation in args:
        series, order = expectation.rsplit("=", 1)
        observed = [float(r[3]) for r in rates if r[0] == series]
        if not observed:
            fail("no rates for series '%s'" % series)
        if abs(observed[-1] - float(order)) > 0.1:
            fail("series '%s': observed order %.3f, theory %s"
                 % (series, observed[-1], order))
        print("series '%s': order %.2f within 0.1 of %s"
              % (series, observed[-1], order))

    for chart in ("error_vs_unknowns.png", "error_vs_wall_time.png"):
        path = os.path.join(directory, chart)
        with open(path, "rb") as f:
            head = f.read(8)
        if os.path.getsize(path) < 1000 or head != b"\x89PNG\r\n\x1a\n":
            fail(chart + " is missing, empty or no PNG")
        print(chart + " written")

    if tolerance is not None:
        error = header.index(next(h for h in header if h.startswith("error")))
        cost = header.index("wall per time unit (s)")
        qualifying = [r for r in rows if float(r[error]) <= tolerance]
        if not qualifying:
            fail("no variant meets the tolerance")
        best = min(qualifying, key=lambda r: float(r[cost]))
        with open(os.path.join(directory, "choice.txt")) as f:
            text = f.read()
        chosen = re.search(r"chose #(\d+)", text)
        if not chosen or chosen.group(1) != best[0]:
            fail("choice.txt does not name variant #%s:\n%s" % (best[0], text))
        print("the model choice is variant #%s, as recomputed from results.csv"
              % best[0])
        if not os.path.isfile(os.path.join(directory, "choice-1", "run.txt")):
            fail("the scene was not run with the choice")
        print("the scene ran with the choice")


main()
