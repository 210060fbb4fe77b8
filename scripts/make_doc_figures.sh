#!/usr/bin/env bash
# The figures in docs/images, remade from the runs behind them: each figure's commands write
# under their example's results/ (as any documented command does), and only this script copies
# the result into docs/images. Run from anywhere in a built checkout (scripts/setup.sh).
#
#   scripts/make_doc_figures.sh --list             # the figures, what each needs and how long
#   scripts/make_doc_figures.sh stability          # one or more figures by name
#   scripts/make_doc_figures.sh all                # every figure (about 4.5 hours)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
source "$root/scripts/lib/cocopp-bin.sh"
images="$root/docs/images"
python=/usr/bin/python3
coarse_wire=(--set mesh.wire_radial_elements=4 --set mesh.wire_axial_elements=153
             --set mesh.film_axial_cells=50 --set mesh.film_radial_cells=3)
# The paper's load-driven wire under the sharp die (the bench of docs/wire-drawing.md's subsection).
load_driven_wire=(--set mesh.wire_model=axisymmetric
                  --set coupling.drive=load --set coupling.omega=0.01 --set die.transition_length=0)

# name | needs | time on 2 cores | docs page
figures=(
  "stability|the tube solvers|2 min|docs/stability.md"
  "tube_side_by_side|the tube solvers|10 s|docs/coupling.md"
  "tube_substeps|the tube solvers|10 s|docs/coupling.md"
  "tube_flow_calculix|CalculiX|15 s|docs/solver-wrappers-calculix.md"
  "openfoam_wedge|OpenFOAM|1 min|docs/solver-wrappers-openfoam.md"
  "wire_drawing_bench|OpenFOAM and CalculiX|20 min|docs/wire-drawing.md"
  "wire_drawing_bench_load_driven|OpenFOAM and CalculiX|8 min|docs/wire-drawing.md"
  "wire_drawing|OpenFOAM and CalculiX|45 min|docs/wire-drawing.md"
  "turek_hron_fsi1|OpenFOAM and CalculiX|4 min|docs/validation-turek-hron.md"
  "turek_hron_fsi2|OpenFOAM and CalculiX|35 min|docs/validation-turek-hron.md"
  "turek_hron_fsi2_level2|OpenFOAM (2 MPI ranks) and CalculiX|60 min|docs/validation-turek-hron.md"
  "turek_hron_fsi3|OpenFOAM and CalculiX|30 min|docs/validation-turek-hron.md"
  "turek_hron_fsi3_bench|turek_hron_fsi3's run|45 min|docs/validation-turek-hron.md"
  "turek_hron_substeps|OpenFOAM and CalculiX|13 min|docs/coupling.md"
)

publish() {  # publish <file under results/> <name in docs/images>
  cp "$1" "$images/$2"
  echo "make_doc_figures: docs/images/$2 from ${1#"$root"/}"
}

make_stability() {
  local example="$root/examples/tube/stability"
  "$cocopp" bench --quiet "$example/stability.yaml"
  "$python" "$root/scripts/tube_modes.py" "$example/results/stability" \
    -o "$example/results/stability/stability.png"
  publish "$example/results/stability/stability.png" stability.png
}

make_tube_side_by_side() {  # serial against parallel coupling: error against run time
  local example="$root/examples/tube/bench"
  "$cocopp" bench --quiet "$example/side_by_side.yaml"
  publish "$example/results/side_by_side/bench.png" tube-side-by-side.png
}

make_tube_substeps() {  # each solver at its own time step: error against run time
  local example="$root/examples/tube/bench"
  "$cocopp" bench --quiet "$example/substeps.yaml"
  publish "$example/results/substeps/bench.png" tube-substeps.png
}

make_tube_flow_calculix() {
  local tube="$root/examples/tube"
  "$cocopp" run --quiet "$tube/flow_calculix/case.yaml" || [ $? -eq 3 ]
  "$cocopp" run --quiet "$tube/flow_calculix/case_axisymmetric.yaml" || [ $? -eq 3 ]
  "$cocopp" run --quiet "$tube/flow_calculix/equivalent_tube/case.yaml" || [ $? -eq 3 ]
  "$cocopp" run --quiet "$tube/flow_structure/case.yaml" || [ $? -eq 3 ]
  "$python" "$tube/flow_calculix/compare.py"
  publish "$tube/flow_calculix/results/tube-flow-calculix.png" tube-flow-calculix.png
}

make_openfoam_wedge() {
  "$root/examples/tube/openfoam_wedge/run.sh"
  publish "$root/examples/tube/openfoam_wedge/results/openfoam_wedge_vs_1d.png" \
    openfoam_wedge_vs_1d.png
}

wire_drawing_bench() {  # wire_drawing_bench <image> <bench.sh options>: run, plot, publish
  local example="$root/examples/wire_drawing" image=$1
  shift
  "$example/bench.sh" "$@"
  "$python" "$root/scripts/plot_bench.py" "$example/results/bench/bench.json" \
    -o "$example/results/bench/bench.png"
  publish "$example/results/bench/bench.png" "$image"
}

make_wire_drawing_bench() {  # the case as it ships: the wire driven by displacement
  wire_drawing_bench wire-drawing-bench.png "${coarse_wire[@]}"
}

make_wire_drawing_bench_load_driven() {  # the paper's load-driven wire (into the same results/bench)
  wire_drawing_bench wire-drawing-bench-load-driven.png --bench bench_load_driven.yaml \
    "${coarse_wire[@]}" "${load_driven_wire[@]}"
}

make_wire_drawing() {  # the paper's 80 steps, then 40 with the die held closed (steady drawing)
  local example="$root/examples/wire_drawing"
  "$example/run.sh" --name steady --set time.steady_steps=40
  "$python" "$example/plot.py" "$example/results/steady" --until 80
  publish "$example/results/steady/wire-drawing.png" wire-drawing.png
  "$python" "$example/checks.py" "$example/results/steady"
  "$python" "$example/steady.py" "$example/results/steady"
  publish "$example/results/steady/wire-drawing-steady.png" wire-drawing-steady.png
}

make_turek_hron_fsi1() {
  "$root/examples/turek_hron/fsi/run.sh" fsi1
  publish "$root/examples/turek_hron/fsi/results/fsi1/turek-hron.png" turek-hron-fsi1.png
}

make_turek_hron_fsi2() {
  "$root/examples/turek_hron/fsi/run.sh" fsi2
  publish "$root/examples/turek_hron/fsi/results/fsi2/turek-hron.png" turek-hron-fsi2.png
}

make_turek_hron_fsi2_level2() {
  "$root/examples/turek_hron/fsi/run.sh" fsi2 --name fsi2_level2 --level 2 --dt 0.004 \
    --pressure-rel-tol 0.05 --cores 2
  publish "$root/examples/turek_hron/fsi/results/fsi2_level2/turek-hron.png" turek-hron-fsi2-level2.png
}

make_turek_hron_fsi3() {
  "$root/examples/turek_hron/fsi/run.sh" fsi3 --dt 0.002 --end-time 8
  publish "$root/examples/turek_hron/fsi/results/fsi3/turek-hron.png" turek-hron-fsi3.png
}

make_turek_hron_fsi3_bench() {  # after turek_hron_fsi3: its run at 8 s is the bench's base
  local example="$root/examples/turek_hron/fsi"
  "$cocopp" bench --no-plot "$example/bench_fsi3.yaml"
  "$python" "$example/bench_residuals.py" "$example/results/bench_fsi3"
  publish "$example/results/bench_fsi3/residuals.png" turek-hron-fsi3-residuals.png
}

make_turek_hron_substeps() {  # the fluid at its own time step: six runs of FSI3's first second
  local example="$root/examples/turek_hron/fsi"
  "$python" "$example/substeps.py"
  publish "$example/results/substeps.png" turek-hron-substeps.png
}

if [ $# -eq 0 ] || [ "$1" = --help ] || [ "$1" = -h ]; then
  sed -n '2,8p' "$0"
  exit 0
fi
if [ "$1" = --list ]; then
  printf '%-20s %-24s %-8s %s\n' figure needs time page
  for entry in "${figures[@]}"; do
    IFS='|' read -r name needs time page <<< "$entry"
    printf '%-20s %-24s %-8s %s\n' "$name" "$needs" "$time" "$page"
  done
  exit 0
fi
names=("$@")
if [ "$1" = all ]; then
  names=()
  for entry in "${figures[@]}"; do names+=("${entry%%|*}"); done
fi
for name in "${names[@]}"; do
  known=0
  for entry in "${figures[@]}"; do [ "${entry%%|*}" = "$name" ] && known=1; done
  if [ $known = 0 ]; then
    echo "make_doc_figures: no figure '$name' (--list shows them)" >&2
    exit 2
  fi
done
cocopp=$(cocopp_executable "$root")
for name in "${names[@]}"; do "make_$name"; done
