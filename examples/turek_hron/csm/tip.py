#!/usr/bin/env python3
"""The flag's tip A in a CSM run's results against Turek & Hron (2006):
    tip.py csm1|csm2|csm3 results/case.h5
CSM1, CSM2: u(A) after the step; CSM3: mean, amplitude and frequency of u_y(A) over its last two
periods (from its maxima; u_x's mean and amplitude between the same times)."""
import sys

from cocopp.results import ResultsFile

REFERENCE = {"csm1": {"ux": -7.187e-3, "uy": -66.10e-3},
             "csm2": {"ux": -0.4690e-3, "uy": -16.97e-3},
             "csm3": {"uy mean": -63.607e-3, "uy amplitude": 65.160e-3, "frequency": 1.0995,
                      "ux mean": -14.305e-3, "ux amplitude": 14.305e-3}}


def tip_history(path):
    """u(A) per step: the partner's last point (x = 0.6) takes the tip's displacement."""
    with ResultsFile(path) as results:
        displacement = results.values("x", "flag_top", "displacement")
        return results.times, displacement[:, -1, 0], displacement[:, -1, 1]


def maxima(times, values):
    found = []
    for k in range(1, len(values) - 1):
        a, b, c = values[k - 1], values[k], values[k + 1]
        if b >= a and b > c:
            offset = 0.5 * (a - c) / (a - 2 * b + c)
            found.append(times[k] + offset * (times[k + 1] - times[k]))
    return found


def main():
    test, path = sys.argv[1], sys.argv[2]
    times, ux, uy = tip_history(path)
    if test in ("csm1", "csm2"):
        values = {"ux": ux[-1], "uy": uy[-1]}
    else:
        peaks = maxima(times, uy)
        if len(peaks) < 3:
            sys.exit("tip.py: fewer than two periods of u_y in " + path)
        window = (times >= peaks[-3]) & (times <= peaks[-1])
        values = {"uy mean": 0.5 * (uy[window].max() + uy[window].min()),
                  "uy amplitude": 0.5 * (uy[window].max() - uy[window].min()),
                  "frequency": 2.0 / (peaks[-1] - peaks[-3]),
                  "ux mean": 0.5 * (ux[window].max() + ux[window].min()),
                  "ux amplitude": 0.5 * (ux[window].max() - ux[window].min())}
    for name, value in values.items():
        reference = REFERENCE[test][name]
        print(f"{test} {name:13s} {value: .5e}  reference {reference: .5e}  "
              f"{100 * (value / reference - 1):+.2f} %")


if __name__ == "__main__":
    main()
