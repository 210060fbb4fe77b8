#!/usr/bin/python3
"""The figures (cocopp.plot in python/cocopp, plot_results.py, plot_bench.py) and `cocopp bench
--quiet`, ctest `plots`: on a tube run with a watchpoint, each figure holds the numbers of the
results file it was drawn from (residuals as the criterion measures them and its tolerance,
iterations per step, the history at a point, the space-time map, the animation's frames), and
the bench figure has its three costs.

usage: test_plots.py BIN_DIR SOURCE_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_install import check, run  # noqa: E402


def tube_run(bin_dir, source, scratch, name, criterion):
    """The flow-structure tube, 30 steps, a watchpoint at cell 50's centre."""
    directory = os.path.join(scratch, name)
    shutil.copytree(os.path.join(source, "examples/tube/flow_structure"), directory,
                    ignore=shutil.ignore_patterns("results", "output", "*.log"))
    with open(os.path.join(directory, "case.yaml")) as f:
        text = f.read()
    text = text.replace("number_of_timesteps: 100", "number_of_timesteps: 30\n  watchpoints: "
                        "[{name: mid, coordinates: [0, 0.005, 0.00025]}]")
    start = text.index("  convergence_criterion:")
    end = text.index("solver_wrappers:")
    text = text[:start] + criterion + text[end:]
    with open(os.path.join(directory, "case.yaml"), "w") as f:
        f.write(text)
    # The run with steps at the iteration limit ends stalled, exit code 3: a result here.
    run([os.path.join(bin_dir, "cocopp"), "run", "--quiet", "case.yaml"], cwd=directory,
        accepted=(0, 3))
    return os.path.join(directory, "results", "case.h5")


def main():
    bin_dir, source = sys.argv[1], sys.argv[2]
    sys.path.insert(0, os.path.join(source, "python"))
    from cocopp.plot import bench, interface, residuals
    from cocopp.results import ResultsFile, read_bench

    with tempfile.TemporaryDirectory(prefix="cocopp-plots-") as scratch:
        relative = tube_run(bin_dir, source, scratch, "relative", """  convergence_criterion:
    type: or
    criteria:
      - {type: relative_norm, tolerance: 1.0e-6}
      - {type: iteration_limit, maximum: 15}
""")
        absolute = tube_run(bin_dir, source, scratch, "absolute", """  convergence_criterion:
    type: or
    criteria:
      - {type: absolute_norm, tolerance: 1.0e-12}
      - {type: iteration_limit, maximum: 4}
""")
        with ResultsFile(relative) as results:
            histories = results.residual_histories()
            figure, ax = plt.subplots()
            residuals.plot_residuals(ax, results)
            lines = [line for line in ax.get_lines() if len(line.get_xdata()) > 1]
            step1 = histories[0][1]
            check(np.allclose(lines[0].get_ydata(), step1 / step1[0]),
                  "relative criterion: residuals drawn relative to the step's first")
            tolerance_lines = [line for line in ax.get_lines()
                               if list(line.get_ydata()) == [1e-6, 1e-6]]
            check(len(tolerance_lines) == 1, "relative criterion: the tolerance line at 1e-6")
            plt.close(figure)

            figure, ax = plt.subplots()
            residuals.plot_iterations(ax, results)
            heights = sorted(int(p.get_height()) for p in ax.patches)
            check(heights == sorted(len(h[1]) for h in histories),
                  f"a bar per step with its iterations ({sum(heights)} in all)")
            plt.close(figure)

            series, where = results.watchpoint_series("mid")
            watched = results.file["watchpoints/mid/pressure"][:, 0, 0]
            check(np.array_equal(series["pressure"][1][:, 0], watched)
                  and np.allclose(where, [0, 0.005, 0.00025]),
                  "the watchpoint's history is its values in the file")
            nearest, at = results.nearest_point_series([0, 0.005, 0.00025])
            check(np.array_equal(nearest["pressure"][1][:, 0],
                                 results.file["y/wall/pressure"][:, 50, 0])
                  and np.allclose(at, [0, 0.005, 0.00025]),
                  "--point takes the nearest interface point's values")

            figure, ax = plt.subplots()
            interface.plot_space_time(ax, results, "pressure")
            mesh = ax.collections[0].get_array().reshape(len(results.steps), -1)
            check(np.array_equal(mesh, results.file["y/wall/pressure"][:, :, 0]),
                  "the space-time map holds pressure per step and point")
            plt.close(figure)

            gif = os.path.join(scratch, "pressure.gif")
            frames = interface.animate(results, "pressure", gif, frames=10)
            with Image.open(gif) as image:
                check(frames == 10 and image.n_frames == 10, "the animation has its 10 frames")

        with ResultsFile(absolute) as results:
            figure, ax = plt.subplots()
            residuals.plot_residuals(ax, results)
            step1 = results.residual_histories()[0][1]
            line = [line for line in ax.get_lines() if len(line.get_xdata()) > 1][0]
            check(np.allclose(line.get_ydata(), step1)
                  and any(list(line.get_ydata()) == [1e-12, 1e-12] for line in ax.get_lines()),
                  "absolute criterion: the 2-norms and the tolerance line at 1e-12")
            check(any(not h[2] for h in results.residual_histories()),
                  "some steps at the iteration limit (drawn dashed, red bars)")
            plt.close(figure)

        # The command line, every option.
        script = os.path.join(source, "scripts", "plot_results.py")
        output = run(["/usr/bin/python3", script, relative, "--history", "mid", "--space-time",
                      "pressure", "--animate", "displacement"])
        stem = relative[:-3]
        for made in (".png", "_history.png", "_space_time_pressure.png", "_displacement.gif"):
            check(os.path.getsize(stem + made) > 1000 and f"wrote {stem}{made}" in output,
                  f"plot_results.py wrote {os.path.basename(stem + made)}")
        missing = subprocess.run(["/usr/bin/python3", script, relative, "--history", "nowhere"],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(missing.returncode != 0 and "no watchpoint 'nowhere'" in missing.stdout
              and "it has mid" in missing.stdout, "an unknown watchpoint is named")

        # cocopp bench --quiet, and its figure against three costs.
        tube = os.path.join(scratch, "tube")
        shutil.copytree(os.path.join(source, "examples/tube"), tube,
                        ignore=shutil.ignore_patterns("results", "output",
                                                      "*.log"))
        quiet = run([os.path.join(bin_dir, "cocopp"), "bench", "--quiet", "bench.yaml"],
                    cwd=os.path.join(tube, "bench"))
        run_lines = [line for line in quiet.splitlines() if line.startswith("bench run ")]
        check(len(run_lines) == 7 and "cocopp 0.1.0: case" not in quiet
              and "diverged after 0 steps" in run_lines[-1],
              "bench --quiet: one line per run, no run headers")
        report = read_bench(os.path.join(tube, "bench", "results", "bench"))
        check(all(r["solver_time"] > 0 for r in report["runs"] if r["steps_completed"] > 0),
              "bench.json has each run's solver time")
        figure = bench.plot_bench(report, os.path.join(scratch, "bench.png"))
        labels = [ax.get_xlabel() for ax in figure.axes]
        check(labels == ["wall time [s]", "coupling iterations (all steps)",
                         "time in the solvers [s]"], "the bench figure has its three costs")
        points = figure.axes[1].collections
        iterations = sorted(float(c.get_offsets()[0][0]) for c in points)
        expected = sorted(r["solver_calls"] / 2 for r in report["runs"]
                          if r["name"] != "reference" and r["displacement_error"] is not None)
        check(iterations == expected, "each run at its coupling iterations")
    print("plots: all checks passed")


if __name__ == "__main__":
    main()
