#pragma once
// `cocopp bench`, part 4: the report: the table on the terminal, bench.csv, bench.json and the
// error-against-run-time plot (docs/bench.md).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "coupler/app/bench_comparison.hpp"
#include "coupler/app/bench_file.hpp"

namespace cocopp {

/// "<case>/<variant>", or the variant's name without cases.
std::string label(const BenchRow& row);

void print_table(const std::vector<BenchRow>& rows);

/// bench.json's `reference`: the results file, "none", or one file per case of a sweep.
nlohmann::json describe_references(const BenchFile& bench);

/// bench.csv and bench.json in the output directory.
void write_outputs(const BenchFile& bench, const nlohmann::json& reference,
                   const std::vector<BenchRow>& rows);

/// bench.png, drawn by plot_bench.py (installed with cocopp); a failure is a warning.
void plot(const BenchFile& bench);

}  // namespace cocopp
