// cocopp-ccx: CalculiX's ccx as one persistent solver process of the cocopp coupler.
//
// ccx keeps control of its own increment loop (nonlingeo.c), so the two sides meet at the hooks
// of cocopp_ccx_hooks.h: ccx runs in a thread of its own and the SDK's serve() in the main
// thread; a request of the coupler (solve, commit, stop) is handed to the ccx thread where it
// waits in a hook, and the main thread waits for its answer. One coupler time step is one
// stretch of ccx's step time: a coupling iteration solves it from a checkpoint of ccx's state
// at its start (the arrays ccx's own cut-back restores), a commit lets ccx write its results
// and go on. Nothing goes through files but ccx's own results.
//
// The interface comes from `cocopp_interface.txt` in the working directory, written by the
// `calculix` wrapper (solver_wrappers/calculix, mode persistent) next to the deck, whose step
// has a placeholder load for every entry (so that ccx allocates it); its format is defined once,
// for both sides, in core/data/calculix_interface_file.hpp.
#include <pthread.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/data/calculix_interface_file.hpp"
#include "solvers/calculix/cocopp_ccx_hooks.h"
#include "solvers/sdk/solver_sdk.hpp"

extern "C" int cocopp_ccx_main(int argc, char** argv);  // ccx's main, renamed at build time

// ccx's interpolation of its 3D expansion of 1D/2D elements back onto their own nodes, as it
// prints and writes them (map3dto1d2d.f; prototype as in ccx's CalculiX.h).
extern "C" void map3dto1d2d_(double* yn, int* ipkon, int* inum, int* kon, char* lakon, int* nfield,
                             int* nk, int* ne, char* cflag, double* co, double* vold, int* iforce,
                             int* mi, int* ielprop, double* prop);

namespace {

using cocopp::calculix::InterfaceFile;

/// The state a coupling iteration starts from: what ccx's cut-back restores, and its counters.
class Checkpoint {
 public:
  void save(const cocopp_ccx_increment& inc) {
    arrays_.clear();
    for (const auto& [pointer, size] : arrays(inc))
      arrays_.emplace_back(*pointer, *pointer + (*pointer != nullptr ? size : 0));
    scalars_ = {*inc.theta,    *inc.allwk,    *inc.dampwk,  inc.energy[0],
                inc.energy[1], inc.energy[2], inc.energy[3]};
    jprint_ = *inc.jprint;
  }
  void restore(const cocopp_ccx_increment& inc) const {
    const auto list = arrays(inc);
    for (std::size_t i = 0; i < list.size(); ++i)
      if (*list[i].first != nullptr)
        std::copy(arrays_[i].begin(), arrays_[i].end(), *list[i].first);
    *inc.theta = scalars_[0];
    *inc.allwk = scalars_[1];
    *inc.dampwk = scalars_[2];
    for (int k = 0; k < 4; ++k) inc.energy[k] = scalars_[3 + k];
    *inc.jprint = jprint_ - 1;  // the loop's top counts the increment again
  }

 private:
  static std::vector<std::pair<double**, std::size_t>> arrays(const cocopp_ccx_increment& inc) {
    const auto n = [](int value) { return static_cast<std::size_t>(value); };
    const std::size_t nodal = n(*inc.mt) * n(*inc.nk);
    const std::size_t stresses = 6 * n(inc.mi[0]) * n(*inc.ne0);
    const std::size_t equations = n(inc.neq[1]);
    std::vector<std::pair<double**, std::size_t>> list = {
        {inc.vold, nodal},
        {inc.f, equations},
        {inc.sti, stresses},
        {inc.eme, stresses},
        {inc.xbounact, n(*inc.nboun)},
        {inc.xstate, n(*inc.nstate) * n(inc.mi[0]) * n(*inc.ne0)}};
    if (*inc.nener == 1) list.push_back({inc.ener, n(inc.mi[0]) * n(*inc.ne0)});
    if (*inc.ithermal == 1 || *inc.ithermal >= 3) list.push_back({inc.t1act, n(*inc.nk)});
    if (*inc.nmethod == 4)
      for (auto [array, size] : {std::pair{inc.veold, nodal},
                                 {inc.accold, nodal},
                                 {inc.fnext, nodal},
                                 {inc.fext, equations},
                                 {inc.cv, equations}})
        list.push_back({array, size});
    return list;
  }

  std::vector<std::vector<double>> arrays_;
  std::vector<double> scalars_;
  int jprint_ = 0;
};

/// The coupler's side of the hand-over: requests to the ccx thread, answers back.
class CoupledCcx : public cocopp::sdk::Solver {
 public:
  CoupledCcx(std::vector<std::string> ccx_arguments) : ccx_arguments_(std::move(ccx_arguments)) {}

  // --- main thread (the SDK) ---

  cocopp::sdk::InterfaceDescription initialize(const cocopp::sdk::RunInfo& run) override {
    if (run.timestep_start > 0)
      throw std::runtime_error("cocopp-ccx cannot restart a run (it keeps no restart data)");
    lists_ = InterfaceFile::read(InterfaceFile::kName);
    start_ccx();
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return ccx_waiting_ || ccx_done_; });
    if (!ccx_waiting_) throw std::runtime_error(ccx_gone_message("before its first increment"));
    return description();
  }

  void initialize_step(std::int32_t step, double time) override {
    step_ = step;
    step_end_time_ = time;
  }

  std::vector<double> solve(const std::vector<double>& input) override {
    ++solves_;
    std::unique_lock lock(mutex_);
    post(lock, Request::kSolve, input);
    changed_.wait(lock, [&] { return output_ready_ || ccx_done_ || !error_.empty(); });
    if (!error_.empty()) throw std::runtime_error(error_);
    if (!output_ready_)
      throw std::runtime_error(ccx_gone_message("in time step " + std::to_string(step_)));
    output_ready_ = false;
    return output_;
  }

  void finalize_step() override {
    std::unique_lock lock(mutex_);
    post(lock, Request::kCommit, {});
    // Until ccx has written the step's results and waits at the next step's start.
    changed_.wait(lock, [&] { return ccx_waiting_ || ccx_done_; });
  }

  void finalize() override {
    {
      std::unique_lock lock(mutex_);
      if (!ccx_done_) post(lock, Request::kStop, {});
    }
    if (ccx_started_) pthread_join(ccx_thread_, nullptr);
    ccx_started_ = false;
    // For the benchmark (bench_calculix_persistent) and the curious: what the hand-over costs.
    if (solves_ > 0)
      std::printf(
          "\ncocopp-ccx: %ld coupling iterations; its own work (checkpoints, loads, "
          "displacements) %.3f ms per iteration\n",
          solves_, 1e3 * (hook_seconds_ - wait_seconds_) / static_cast<double>(solves_));
  }

  /// The hooks' time, their waits for the coupler excluded (hook_seconds_ - wait_seconds_).
  void add_hook_time(double seconds) { hook_seconds_ += seconds; }

  // --- ccx thread (the hooks) ---

  cocopp_ccx_action increment_start(cocopp_ccx_increment& inc) {
    if (starting_) {  // a repeated coupling iteration, reset in increment_end
      start_increments(inc);
      return COCOPP_CCX_CONTINUE;
    }
    if (in_step_) {  // the next increment of the coupler's time step
      clamp_increment(inc);
      return COCOPP_CCX_CONTINUE;
    }
    if (!inc_) inc_ = &inc;
    std::unique_lock lock(mutex_);
    const Request request = wait_for_request(lock);
    if (request != Request::kSolve) return stop(inc);
    checkpoint_.save(inc);
    step_start_theta_ = *inc.theta;
    begin_iteration(inc);
    start_increments(inc);
    return COCOPP_CCX_CONTINUE;
  }

  void apply_loads(cocopp_ccx_loads& loads) {
    if (!in_step_) return;  // ccx's loads before the first step: the placeholders' zeros
    if (force_entries_.empty() && pressure_entries_.empty()) find_entries(loads);
    const double span = step_end_theta_ - step_start_theta_;
    const double fraction = lists_.ramp && span > 0
                                ? std::clamp((loads.reltime - step_start_theta_) / span, 0., 1.)
                                : 1.0;
    for (std::size_t i = 0; i < pressure_entries_.size(); ++i)
      loads.xloadact[2 * pressure_entries_[i]] =
          committed_[i] + fraction * (target_[i] - committed_[i]);
    for (std::size_t i = 0; i < force_entries_.size(); ++i) {
      const std::size_t k = force_values_[i];
      loads.xforcact[force_entries_[i]] =
          lists_.force_scale * (committed_[k] + fraction * (target_[k] - committed_[k]));
    }
  }

  cocopp_ccx_action increment_end(cocopp_ccx_increment& inc) {
    if (*inc.theta < step_end_theta_ - kThetaTolerance) {
      --*inc.jprint;  // a part of the step: results only for whole coupler steps
      return COCOPP_CCX_REPEAT;
    }
    std::unique_lock lock(mutex_);
    output_ = displacements(inc);
    output_ready_ = true;
    changed_.notify_all();
    const Request request = wait_for_request(lock);
    if (request == Request::kCommit) {
      committed_ = target_;
      in_step_ = false;
      return COCOPP_CCX_CONTINUE;
    }
    if (request == Request::kStop) {
      stop(inc);
      return COCOPP_CCX_REPEAT;
    }
    checkpoint_.restore(inc);
    begin_iteration(inc);
    return COCOPP_CCX_REPEAT;
  }

  void ccx_finished() {
    std::lock_guard lock(mutex_);
    ccx_done_ = true;
    ccx_waiting_ = false;
    changed_.notify_all();
  }

  const std::vector<std::string>& ccx_arguments() const { return ccx_arguments_; }
  /// Whether ccx's thread still runs (it waits in a hook after an error the coupler was told).
  bool ccx_running() const { return ccx_started_; }

 private:
  enum class Request { kNone, kSolve, kCommit, kStop };
  static constexpr double kThetaTolerance = 1e-9;

  void post(std::unique_lock<std::mutex>& lock, Request request, std::vector<double> input) {
    changed_.wait(lock, [&] { return ccx_waiting_ || ccx_done_; });
    if (ccx_done_) return;
    request_ = request;
    if (request == Request::kSolve) input_ = std::move(input);
    ccx_waiting_ = false;
    changed_.notify_all();
  }

  Request wait_for_request(std::unique_lock<std::mutex>& lock) {
    const auto start = std::chrono::steady_clock::now();
    ccx_waiting_ = true;
    changed_.notify_all();
    changed_.wait(lock, [&] { return request_ != Request::kNone; });
    wait_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::exchange(request_, Request::kNone);
  }

  cocopp_ccx_action stop(cocopp_ccx_increment& inc) {
    *inc.theta = 1.0;  // ends ccx's step: it writes its last files and returns
    *inc.jprint = 0;   // the committed steps' results are written already
    return COCOPP_CCX_STOP;
  }

  void begin_iteration(cocopp_ccx_increment& inc) {
    target_ = input_;
    if (committed_.empty()) committed_.assign(target_.size(), 0.0);
    step_end_theta_ = (step_end_time_ - *inc.ttime) / *inc.tper;
    in_step_ = true;
    starting_ = true;
  }

  // Every coupling iteration's increments start as a ccx step's do (nonlingeo.c before its
  // loop), so that they follow the same sizes as in one ccx run per iteration: the deck's
  // first increment (a fraction of the coupler step, as the deck's of its step), ccx's
  // increment control and its mean force for the convergence check afresh, the increments
  // counted from 1 (against *STEP, INC=).
  void start_increments(cocopp_ccx_increment& inc) {
    starting_ = false;
    *inc.dtheta = lists_.initial_increment / *inc.tper;
    *inc.dthetaref = *inc.dtheta;
    *inc.istab = 0;
    *inc.iinc = 1;
    // The mean force is a running mean over the step's converged increments: left to run over
    // every coupling iteration of the run, it falls behind a growing load (0.06 against forces
    // of 3.9 in a flow started from rest) and the check asks ccx for what round-off denies it.
    inc.qam[0] = inc.qam[1] = 0.0;
    *inc.jnz = 0;
    *inc.energym = 0.0;
    clamp_increment(inc);
  }

  void clamp_increment(cocopp_ccx_increment& inc) const {
    const double left = step_end_theta_ - *inc.theta;
    if (*inc.dtheta > left || left - *inc.dtheta < kThetaTolerance) *inc.dtheta = left;
  }

  // As ccx prints them: a plane or axisymmetric model's nodes take the mean across the 3D
  // expansion ccx solves (its own values there are not kept up to date).
  std::vector<double> displacements(const cocopp_ccx_increment& inc) const {
    std::vector<double> u;
    u.reserve(3 * lists_.displacement_nodes.size());
    const std::size_t size = static_cast<std::size_t>(*inc.mt) * *inc.nk;
    std::vector<double> v(*inc.vold, *inc.vold + size);
    std::vector<int> inum(static_cast<std::size_t>(*inc.nk), 0);
    int nfield = *inc.mt, iforce = 0;
    char cflag = ' ';
    map3dto1d2d_(v.data(), *inc.ipkon, inum.data(), *inc.kon, *inc.lakon, &nfield, inc.nk, inc.ne,
                 &cflag, *inc.co, *inc.vold, &iforce, inc.mi, inc.ielprop, inc.prop);
    const double* vold = v.data();
    for (int node : lists_.displacement_nodes)
      for (int k = 1; k <= 3; ++k)
        u.push_back(vold[static_cast<std::size_t>(*inc.mt) * (node - 1) + k]);
    return u;
  }

  // The placeholders the wrapper's deck gave: which entries of ccx's load arrays are ours.
  void find_entries(const cocopp_ccx_loads& loads) {
    std::map<std::pair<int, std::string>, int> by_face;
    for (int i = 0; i < loads.nload; ++i) {
      std::string label(loads.sideload + 20 * i, 20);
      label.erase(label.find_last_not_of(' ') + 1);
      by_face[{loads.nelemload[2 * i], label}] = i;
    }
    for (const auto& [element, face] : lists_.pressure_faces) {
      const auto found = by_face.find({element, "P" + std::to_string(face + lists_.face_offset)});
      if (found == by_face.end()) {
        std::string has;
        for (const auto& [key, index] : by_face)
          if (key.first == element) has += " " + key.second;
        fail("the deck has no *DLOAD placeholder for element " + std::to_string(element) +
             ", face P" + std::to_string(face) +
             (has.empty() ? std::string(" (none for that element)") : "; it has" + has));
      }
      pressure_entries_.push_back(found->second);
    }
    std::map<std::pair<int, int>, int> by_dof;
    for (int i = 0; i < loads.nforc; ++i) by_dof[{loads.nodeforc[2 * i], loads.ndirforc[i]}] = i;
    // The input has 3 force components per node; a plane model takes the first 2.
    std::size_t value = pressure_entries_.size();
    for (int node : lists_.force_nodes)
      for (int dof = 1; dof <= 3; ++dof, ++value) {
        if (dof > lists_.force_dofs) continue;
        const auto found = by_dof.find({node, dof});
        if (found == by_dof.end())
          fail("the deck has no *CLOAD placeholder for node " + std::to_string(node) + ", dof " +
               std::to_string(dof));
        force_entries_.push_back(found->second);
        force_values_.push_back(value);
      }
    if (target_.size() != value)
      fail("the coupler sent " + std::to_string(target_.size()) +
           " load values; the interface has " + std::to_string(value));
  }

  // An error inside a hook cannot unwind through ccx's C and Fortran: it goes to the main
  // thread, which reports it to the coupler and ends the process; this thread waits for that.
  [[noreturn]] void fail(const std::string& message) {
    std::unique_lock lock(mutex_);
    error_ = "cocopp-ccx: " + message;
    changed_.notify_all();
    for (;;) changed_.wait(lock);
  }

  std::string ccx_gone_message(const std::string& when) const {
    return "ccx ended " + when +
           " (a deck error, or its step's time period is shorter than the coupled run: see the "
           "*ERROR lines in this log)";
  }

  cocopp::sdk::InterfaceDescription description() const {
    cocopp::sdk::InterfaceDescription d;
    const double* co = *inc_->co;
    const auto part = [&](const std::string& name, const std::vector<int>& ids,
                          std::vector<std::string> inputs, std::vector<std::string> outputs,
                          const std::vector<std::vector<double>>& coordinates) {
      cocopp::sdk::ModelPart p;
      p.name = name;
      for (std::size_t i = 0; i < ids.size(); ++i) {
        p.ids.push_back(ids[i]);
        p.coordinates.insert(p.coordinates.end(), coordinates[i].begin(), coordinates[i].end());
      }
      p.input_variables = std::move(inputs);
      p.output_variables = std::move(outputs);
      d.model_parts.push_back(std::move(p));
    };
    const auto node_coordinates = [&](const std::vector<int>& nodes) {
      std::vector<std::vector<double>> c;
      for (int node : nodes)
        c.push_back({co[3 * (node - 1)], co[3 * (node - 1) + 1], co[3 * (node - 1) + 2]});
      return c;
    };
    if (!lists_.pressure_faces.empty()) {
      std::vector<int> ids;
      for (const auto& [element, face] : lists_.pressure_faces) ids.push_back(element * 10 + face);
      part("pressure_faces", ids, {"pressure"}, {},
           std::vector<std::vector<double>>(ids.size(), {0.0, 0.0, 0.0}));
    }
    if (!lists_.force_nodes.empty())
      part("force_nodes", lists_.force_nodes, {"force"}, {}, node_coordinates(lists_.force_nodes));
    part("displacement_nodes", lists_.displacement_nodes, {}, {"displacement"},
         node_coordinates(lists_.displacement_nodes));
    return d;
  }

  void start_ccx();

  std::vector<std::string> ccx_arguments_;
  InterfaceFile lists_;
  pthread_t ccx_thread_{};
  bool ccx_started_ = false;

  std::mutex mutex_;
  std::condition_variable changed_;
  bool ccx_waiting_ = false;  ///< the ccx thread waits in a hook for a request
  bool ccx_done_ = false;
  Request request_ = Request::kNone;
  std::vector<double> input_;
  std::vector<double> output_;
  bool output_ready_ = false;
  std::string error_;

  // The ccx thread's (and, between requests, the main thread's) view of the step.
  cocopp_ccx_increment* inc_ = nullptr;
  std::int32_t step_ = 0;
  double step_end_time_ = 0.0;
  double step_start_theta_ = 0.0;
  double step_end_theta_ = 0.0;
  bool in_step_ = false;
  bool starting_ = false;  ///< the next increment is a coupling iteration's first
  Checkpoint checkpoint_;
  std::vector<double> committed_;  ///< loads of the last committed step (pressures, forces)
  std::vector<double> target_;     ///< this coupling iteration's
  std::vector<int> pressure_entries_, force_entries_;
  double hook_seconds_ = 0.0, wait_seconds_ = 0.0;
  long solves_ = 0;
  std::vector<std::size_t> force_values_;  ///< each force entry's place in the input
};

CoupledCcx* the_solver = nullptr;

// Each hook timed whole; its waits for the coupler are taken out at the end.
template <class Hook>
auto timed(Hook&& hook) {
  const auto start = std::chrono::steady_clock::now();
  struct Add {
    std::chrono::steady_clock::time_point start;
    ~Add() {
      the_solver->add_hook_time(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  } add{start};
  return hook();
}

extern "C" {
cocopp_ccx_action hook_increment_start(cocopp_ccx_increment* inc) {
  return timed([&] { return the_solver->increment_start(*inc); });
}
void hook_apply_loads(cocopp_ccx_increment* /*inc*/, cocopp_ccx_loads* loads) {
  timed([&] { the_solver->apply_loads(*loads); });
}
cocopp_ccx_action hook_increment_end(cocopp_ccx_increment* inc) {
  return timed([&] { return the_solver->increment_end(*inc); });
}
void* run_ccx(void*) {
  std::vector<std::string> arguments = the_solver->ccx_arguments();
  std::vector<char*> argv;
  for (auto& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  cocopp_ccx_main(static_cast<int>(arguments.size()), argv.data());
  std::fflush(stdout);
  the_solver->ccx_finished();
  return nullptr;
}
}

struct cocopp_ccx_hooks hooks {
  hook_increment_start, hook_apply_loads, hook_increment_end, 0
};

void CoupledCcx::start_ccx() {
  hooks.linear = lists_.linear ? 1 : 0;
  ::cocopp_ccx_hooks = &hooks;
  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  // ccx's Fortran keeps large arrays on the stack; a thread's default stack is smaller than
  // the main thread's may grow to.
  pthread_attr_setstacksize(&attributes, std::size_t{512} << 20);
  const int failed = pthread_create(&ccx_thread_, &attributes, run_ccx, nullptr);
  pthread_attr_destroy(&attributes);
  if (failed != 0)
    throw std::runtime_error("cannot start ccx's thread: " + std::string(std::strerror(failed)));
  ccx_started_ = true;
}

void print_usage(const char* program) {
  std::cout << "usage: " << program
            << " -i JOB\n\n"
               "CalculiX's ccx as a persistent solver of the cocopp coupler: it reads JOB.inp "
               "and its interface\n(cocopp_interface.txt), and the coupler drives its one step "
               "time step by time step, each\ncoupling iteration solved from the step's start "
               "state in memory. The `calculix` wrapper\nstarts it (mode: persistent); see "
               "docs/solver-wrappers-calculix.md.\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (cocopp::sdk::wants_help(argc, argv)) {
    print_usage(argv[0]);
    return 0;
  }
  // ccx ends the process where it gives up (exit in its thread): its last lines, which say
  // why, must be in the log by then.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::vector<std::string> ccx_arguments{"ccx"};
  for (int i = 1; i < argc; ++i) ccx_arguments.emplace_back(argv[i]);
  CoupledCcx solver(ccx_arguments);
  the_solver = &solver;
  const int status = cocopp::sdk::serve(solver, argc, argv);
  // After an error ccx's thread may still wait in a hook on the solver's mutex: end the process
  // without destroying what it waits on.
  std::fflush(stdout);
  if (solver.ccx_running()) std::_Exit(status);
  return status;
}
