"""A variable along the interface: snapshots at chosen steps, a space-time map, an animation."""
import shutil

import matplotlib.animation
import matplotlib.pyplot as plt
import numpy as np

from cocopp.plot.axes import along_axis, label, varying_component


def _message(ax, text):
    ax.text(0.5, 0.5, text, ha="center", transform=ax.transAxes)
    ax.set_axis_off()


def plot_snapshots(ax, results, interface, variable, steps, rows, part=None, component=None,
                   axis=None):
    """The variable along the interface at the given steps (rows of the file)."""
    part = results.find_part(interface, variable, part)
    if not rows:
        return _message(ax, "no completed time step")
    if part is None:
        return _message(ax, f"no '{variable}' in interface {interface}")
    unique = sorted(set(rows))
    data = results.values(interface, part, variable, unique)[[unique.index(r) for r in rows]]
    coordinates = results.coordinates(interface, part)
    a = along_axis(coordinates, axis)
    c = varying_component(data, component)
    order = np.argsort(coordinates[:, a])
    for row_data, step in zip(data, steps):
        ax.plot(coordinates[order, a], row_data[order, c], marker=".", label=f"step {step}")
    ax.set_xlabel(f"initial {'xyz'[a]} (m)")
    ax.set_ylabel(label(variable, data.shape[2], c, results.unit(interface, part, variable)))
    ax.set_title(f"{interface}/{part}/{variable}", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)


def _along(results, variable, part, component, axis):
    """(coordinate along the interface (sorted), values (steps, points), labels)."""
    interface, part = results.find_variable(variable, part)
    coordinates = results.coordinates(interface, part)
    values = results.values(interface, part, variable)
    a = along_axis(coordinates, axis)
    c = varying_component(values, component)
    order = np.argsort(coordinates[:, a])
    text = label(variable, values.shape[2], c, results.unit(interface, part, variable))
    return (coordinates[order, a], values[:, order, c], f"initial {'xyz'[a]} (m)", text,
            f"{interface}/{part}/{variable}")


def plot_space_time(ax, results, variable, part=None, component=None, axis=None):
    """The variable along the interface (horizontal) against time (vertical), as colours."""
    if len(results.steps) == 0:
        return _message(ax, "no completed time step")
    position, values, xlabel, vlabel, title = _along(results, variable, part, component, axis)
    mesh = ax.pcolormesh(position, results.times, values, shading="nearest", cmap="RdBu_r")
    plt.colorbar(mesh, ax=ax, label=vlabel)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("time (s)")
    ax.set_title(f"{title}: space-time", fontsize=9)


def animate(results, variable, output, part=None, component=None, axis=None, frames=100,
            fps=10):
    """The variable along the interface step by step, as a GIF (Pillow) or, for an output ending
    in .mp4, a video (needs ffmpeg). At most `frames` frames, evenly spread over the steps."""
    if len(results.steps) == 0:
        raise SystemExit("no completed time step to animate")
    position, values, xlabel, vlabel, title = _along(results, variable, part, component, axis)
    rows = np.unique(np.linspace(0, len(results.steps) - 1, min(frames, len(results.steps)))
                     .round().astype(int))
    figure, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    (line,) = ax.plot(position, values[rows[0]], marker=".")
    low, high = np.nanmin(values), np.nanmax(values)
    margin = 0.05 * (high - low) if high > low else 1.0
    ax.set_ylim(low - margin, high + margin)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(vlabel)
    ax.grid(True, alpha=0.3)
    caption = ax.set_title("")

    def draw(row):
        line.set_ydata(values[row])
        caption.set_text(f"{title}: step {results.steps[row]}, t = {results.times[row]:.6g} s")
        return line, caption

    movie = matplotlib.animation.FuncAnimation(figure, draw, frames=rows, blit=False)
    if str(output).endswith(".mp4"):
        if not shutil.which("ffmpeg"):
            raise SystemExit("an .mp4 needs ffmpeg (Debian: apt-get install ffmpeg); "
                             "or write a .gif")
        writer = matplotlib.animation.FFMpegWriter(fps=fps)
    else:
        writer = matplotlib.animation.PillowWriter(fps=fps)
    movie.save(output, writer=writer)
    plt.close(figure)
    return len(rows)
