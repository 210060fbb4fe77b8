"""Residual histories against the convergence criterion's tolerance, and iterations per step."""
import matplotlib
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np


def _positive(history):
    return np.where(np.isfinite(history) & (history > 0), history, np.nan)


def plot_residuals(ax, results):
    """Each step's residual history as the criterion measures it (relative to the step's first
    iteration for relative_norm), with the tolerance as a line; dashed: accepted at the
    iteration limit; red: the step the run stopped in."""
    tolerance = results.tolerance()
    relative = tolerance is not None and tolerance[0] == "relative"

    def measured(history):
        history = _positive(np.asarray(history, dtype=float))
        if relative and len(history) and np.isfinite(history[0]):
            return history / history[0]
        return history

    histories = results.residual_histories()
    colors = plt.cm.viridis(np.linspace(0, 1, max(len(histories), 1)))
    for (step, history, converged), color in zip(histories, colors):
        ax.semilogy(np.arange(1, len(history) + 1), measured(history),
                    "-" if converged else "--", marker="." if converged else "x", color=color,
                    linewidth=0.8)
    if histories:
        mappable = plt.cm.ScalarMappable(
            cmap="viridis", norm=matplotlib.colors.Normalize(histories[0][0], histories[-1][0]))
        plt.colorbar(mappable, ax=ax, label="time step")
    unfinished = results.unfinished_step()
    if unfinished:
        step, history = unfinished
        ax.semilogy(np.arange(1, len(history) + 1), measured(history), "-", marker="o",
                    color="red", linewidth=1.5, label=f"step {step}: the run stopped here")
    if tolerance:
        measure, order, value = tolerance
        note = "" if order == "2" else f" (criterion: {order}-norm; the file keeps 2-norms)"
        ax.axhline(value, color="black", linestyle=":", linewidth=1.2,
                   label=f"tolerance {value:g}{note}")
    if tolerance or unfinished:
        ax.legend(fontsize=8)
    what = "relative to the step's first" if relative else "2-norm"
    ax.set_xlabel("coupling iteration")
    ax.set_ylabel(f"residual, {what}")
    ax.set_title(f"residuals per step; {results.criterion}", fontsize=9)
    ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    ax.grid(True, which="both", alpha=0.3)


def plot_iterations(ax, results):
    """Coupling iterations of every step: converged steps blue, steps accepted at the iteration
    limit red, the step the run stopped in as an outline; the average as a line."""
    histories = results.residual_histories()
    steps = np.array([h[0] for h in histories])
    iterations = np.array([len(h[1]) for h in histories])
    converged = np.array([h[2] for h in histories], dtype=bool)
    if len(steps):
        ax.bar(steps[converged], iterations[converged], width=1.0, color="tab:blue",
               label="converged")
        if (~converged).any():
            ax.bar(steps[~converged], iterations[~converged], width=1.0, color="tab:red",
                   label="at the iteration limit")
        ax.axhline(iterations.mean(), color="black", linestyle="--", linewidth=1,
                   label=f"average {iterations.mean():.2f}")
    unfinished = results.unfinished_step()
    if unfinished:
        ax.bar([unfinished[0]], [len(unfinished[1])], width=1.0, fill=False, edgecolor="red",
               label=f"step {unfinished[0]}: stopped")
    ax.set_xlabel("time step")
    ax.set_ylabel("coupling iterations")
    ax.set_title("iterations per time step", fontsize=9)
    ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    ax.legend(fontsize=8)
    ax.grid(True, axis="y", alpha=0.3)
