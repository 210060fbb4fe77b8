// Build and apply time of the `linear` interpolator in 3D: random points on a cylinder surface,
// source and target different random sets of the same size n.
//
//   bench_mapping [--sizes 1000,10000,100000,1000000] [--repeats 5] [--help]
//
// build = Interpolator::initialize (checks, k-d tree, stencils, sparse matrix);
// apply = one consistent mapping of a 3-component field (best of `repeats`).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/case/settings.hpp"
#include "mappers/interpolators/interpolator.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

cocopp::Coordinates random_on_cylinder(Eigen::Index n, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), axial(0.0, 10.0);
  cocopp::Coordinates points(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = angle(engine);
    points.row(i) << std::cos(a), std::sin(a), axial(engine);
  }
  return points;
}

void print_help() {
  std::puts(
      "bench_mapping: build and apply time of the linear 3D interpolator (random points on a\n"
      "cylinder surface, source and target different random sets of n points each).\n"
      "\n"
      "  --sizes a,b,c   point counts (default 1000,10000,100000,1000000)\n"
      "  --repeats k     apply repetitions, the best is reported (default 5)\n"
      "  --help          this text\n"
      "\n"
      "Columns: n, build time [s], apply time for one 3-component field [ms],\n"
      "build / (n log2 n) [ns], apply / n [ns].");
}

std::vector<long> parse_sizes(const std::string& text) {
  std::vector<long> sizes;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) sizes.push_back(std::stol(item));
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes = {1000, 10000, 100000, 1000000};
  int repeats = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      print_help();
      return 0;
    } else if (arg == "--sizes" && i + 1 < argc) {
      sizes = parse_sizes(argv[++i]);
    } else if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "bench_mapping: unknown argument '%s' (see --help)\n", arg.c_str());
      return 2;
    }
  }

  const auto settings = cocopp::Settings::load_string("type: linear", "bench.yaml");
  std::printf("%10s %10s %10s %18s %12s %10s\n", "n", "build s", "apply ms", "build/nlog2n ns",
              "apply/n ns", "fallbacks");
  for (const long n : sizes) {
    const cocopp::Coordinates source = random_on_cylinder(n, 1);
    const cocopp::Coordinates target = random_on_cylinder(n, 2);
    auto mapper = cocopp::InterpolatorRegistry::instance().create(settings);
    const auto build_start = Clock::now();
    mapper->initialize(source, target);
    const double build = seconds_since(build_start);

    const cocopp::RowMatrix field = cocopp::RowMatrix::Random(n, 3);
    double apply = 1e300;
    double checksum = 0.0;
    for (int r = 0; r < repeats; ++r) {
      const auto apply_start = Clock::now();
      const cocopp::RowMatrix mapped = mapper->map(field);
      apply = std::min(apply, seconds_since(apply_start));
      checksum += mapped(0, 0);
    }
    const double n_log_n = double(n) * std::log2(double(n));
    std::printf("%10ld %10.3f %10.3f %18.1f %12.2f %10d\n", n, build, 1e3 * apply,
                1e9 * build / n_log_n, 1e9 * apply / double(n), mapper->quality().fallbacks);
    if (!std::isfinite(checksum)) return 1;
  }
  return 0;
}
