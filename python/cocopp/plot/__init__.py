"""cocopp.plot: figures of a results file and of `cocopp bench` (matplotlib). The scripts
scripts/plot_results.py and scripts/plot_bench.py are thin command lines over it; a script of
one's own draws them into its own axes:

    import matplotlib.pyplot as plt
    from cocopp.results import ResultsFile
    from cocopp.plot import residuals

    with ResultsFile("results/case.h5") as results:
        figure, axes = plt.subplots()
        residuals.plot_residuals(axes, results)

Modules: residuals (residual histories against the criterion's tolerance, iterations per
step), interface (snapshots along the interface, the space-time map, the animation), history
(the variables at a point over time), bench (error against wall time, coupling iterations and
solver time), axes (the coordinate and component a figure shows, and their labels).
"""
