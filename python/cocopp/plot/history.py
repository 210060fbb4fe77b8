"""The variables at a point over time: the series of ResultsFile.watchpoint_series or
ResultsFile.nearest_point_series, one axis per variable."""
import numpy as np

from cocopp.plot.axes import label


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
