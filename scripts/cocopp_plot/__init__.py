"""cocopp_plot: figures from cocopp's results files and bench files (matplotlib, h5py).

The scripts plot_results.py and plot_bench.py are thin command lines over it; in Python:

    from cocopp_plot import ResultsFile, residuals, interface, history, bench
    with ResultsFile("results/case.h5") as results:
        figure, axes = plt.subplots()
        residuals.plot_residuals(axes, results)

Modules: results (reading a results file), residuals (residual histories against the
criterion's tolerance, iterations per step), interface (snapshots along the interface, the
space-time map, the animation), history (the variables at a point over time), bench (error
against wall time, coupling iterations and solver time).
"""
from cocopp_plot.results import ResultsFile  # noqa: F401
