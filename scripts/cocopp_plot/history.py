"""The variables at a point over time: a watchpoint of the run, or the interface point nearest
to given coordinates."""
import sys

import numpy as np

from cocopp_plot.results import label

COMPONENTS = "xyz"


def watchpoint_series(results, name):
    """{variable: (times, values (steps, components), unit)} of a watchpoint and its point."""
    names = results.watchpoint_names()
    if name not in names:
        sys.exit(f"no watchpoint '{name}' in {results.path}"
                 + (f"; it has {', '.join(names)}" if names else
                    " (the run had no settings.watchpoints: use --point X Y Z)"))
    group = results.file["watchpoints"][name]
    series = {str(v): (results.times, group[v][:, 0, :], group[v].attrs.get("unit", ""))
              for v in group if v not in ("ids", "coordinates")}
    return series, group["coordinates"][0]


def nearest_point_series(results, point):
    """The same for the interface point nearest to `point`, on every model part of x and y
    that has the nearest point (the one point of x and of y nearest to it)."""
    point = np.asarray(point, dtype=float)
    series, where = {}, None
    for interface in ("x", "y"):
        group = results.file[interface]
        best = None
        for part in group.attrs["model_parts"]:
            coordinates = group[part]["coordinates"][:]
            if len(coordinates) == 0:
                continue
            index = int(np.argmin(((coordinates - point) ** 2).sum(axis=1)))
            distance = float(np.sqrt(((coordinates[index] - point) ** 2).sum()))
            if best is None or distance < best[0]:
                best = (distance, str(part), index, coordinates[index])
        if best is None:
            continue
        distance, part, index, where = best
        for variable in group[part]:
            if variable in ("ids", "coordinates"):
                continue
            data = group[part][variable]
            series[f"{variable}"] = (results.times, data[:, index, :], data.attrs.get("unit", ""))
    return series, where


def plot_history(axes, series, where):
    """One axis per variable (axes: a list as long as `series`); vector variables with each
    component that varies."""
    for ax, (variable, (times, values, unit)) in zip(axes, series.items()):
        components = values.shape[1]
        varying = [c for c in range(components) if np.ptp(values[:, c]) > 0] or [0]
        for c in varying:
            ax.plot(times, values[:, c], marker=".", markersize=3,
                    label=label(variable, components, c, unit))
        ax.set_ylabel(variable + (f" ({unit})" if unit else ""))
        ax.legend(fontsize=8)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("time (s)")
    axes[0].set_title("at ({:.6g}, {:.6g}, {:.6g})".format(*where), fontsize=9)
