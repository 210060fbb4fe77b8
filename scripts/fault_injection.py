#!/usr/bin/env python3
"""Try to break cocopp as a careful user would, and count what happens (docs/reliability.md).

Every trial runs the flexible tube (examples/tube/flow_structure, longer) in a fresh directory
and injects one fault: a solver killed, stopped or signalled at a random moment, the coupler
signalled or killed (and then restarted), a solver that breaks the protocol (scripts/fault_solver.py), two runs of
one case at once, links planted at the names cocopp writes, a results directory that fills up.
Then it checks what a user would check:

  clean      the run ended by itself with exit code 0, 1, 2 or 3 and, when not 0 or 3, an
             "error:" line
  crash      the coupler died of a signal it was not sent, aborted, or a sanitizer reported
  hang       the coupler was still running long after its timeouts
  orphan     a process started by the run was still alive after the coupler ended
  data lost  a step the coupler reported done is not in a readable results file (with results
             written in batches: more than the last batch of 100 steps), the summary counts
             more steps written than the file holds (where the disk filled up: other than it
             holds), or a planted link's target was written

and prints one row per scenario. Exit code 1 if any trial crashed, hung, left an orphan or lost
data (in the scenarios run), 0 otherwise.

  /usr/bin/python3 scripts/fault_injection.py                    # 10 trials a scenario
  /usr/bin/python3 scripts/fault_injection.py --trials 1         # the CI test's short form
  /usr/bin/python3 scripts/fault_injection.py --scenarios disk_full --trials 3   # root: tmpfs
Needs h5py (Debian's python3-h5py) and the built cocopp (--bin, default: the one the package
cocopp finds, cocopp.executable).
"""
import argparse
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from cocopp import case
from cocopp.executable import find_cocopp
from cocopp.results import ResultsFile, ResultsFileError, results_path

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STEPS = 400
BATCH_STEPS = 100  # results_write_interval > 0: a batch is written at least this often
SOLVER_TIMEOUT = 2.0  # s: a stopped solver is reported after this
HANG_LIMIT = 60.0     # s: a coupler still running after this hangs


def case_text(steps=STEPS, flow=None, transport="pipe", state_interval=0, write_interval=0.0):
    """The tube case of every trial; `flow` replaces the flow solver (its type, name, ...)."""
    flow = flow or {"type": "tube_flow", "name": "flow", "working_directory": "flow"}
    structure = {"type": "tube_structure", "name": "structure", "working_directory": "structure"}
    process = {"timeout": SOLVER_TIMEOUT, "transport": transport}
    criteria = [{"type": "relative_norm", "tolerance": 1.0e-6},
                {"type": "iteration_limit", "maximum": 15}]
    return case.dump({
        "settings": case.flow({"delta_t": 1.0e-4, "number_of_timesteps": steps,
                               "state_interval": state_interval,
                               "results_write_interval": write_interval}),
        "coupled_solver": {
            "type": "iqni", "omega": 0.05,
            "model": case.flow({"type": "ls", "q": 10, "min_significant": 1.0e-12}),
            "predictor": case.flow({"type": "linear"}),
            "convergence_criterion": {"type": "or", "criteria": [case.flow(c) for c in criteria]}},
        "solver_wrappers": [case.flow({**flow, **process}), case.flow({**structure, **process})]})


class Trial:
    """One run of the tube in its own directory."""

    def __init__(self, work, name, binary):
        self.dir = tempfile.mkdtemp(prefix=name + "_", dir=work)
        shutil.copytree(os.path.join(ROOT, "examples/tube/flow_structure/flow"),
                        os.path.join(self.dir, "flow"))
        shutil.copytree(os.path.join(ROOT, "examples/tube/flow_structure/structure"),
                        os.path.join(self.dir, "structure"))
        self.binary = binary
        self.case = os.path.join(self.dir, "case.yaml")
        self.write_case(case_text())
        self.process = None
        self.output_path = None

    def write_case(self, text):
        with open(self.case, "w") as f:
            f.write(text)

    def start(self, tag="run", extra_env=None):
        self.output_path = os.path.join(self.dir, tag + ".out")
        env = dict(os.environ, **(extra_env or {}))
        self.process = subprocess.Popen([self.binary, "run", self.case],
                                        stdout=open(self.output_path, "w"),
                                        stderr=subprocess.STDOUT, env=env,
                                        start_new_session=True)
        return self.process

    def output(self, path=None):
        with open(path or self.output_path, errors="replace") as f:
            return f.read()

    def wait(self, process=None):
        process = process or self.process
        try:
            return process.wait(timeout=HANG_LIMIT), False
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
            return process.returncode, True

    def wait_for_step(self, step, limit=20.0):
        end = time.time() + limit
        while time.time() < end and self.process.poll() is None:
            if re.search(rf"^step +{step} /", self.output(), re.M):
                return True
            time.sleep(0.002)
        return False

    def solver_pid(self, name):
        """The pid of the solver working in <dir>/<name> (from /proc)."""
        for pid in processes_in(os.path.join(self.dir, name)):
            return pid
        return None

    def last_reported_step(self, text):
        steps = re.findall(r"^step +(\d+) /", text, re.M)
        return int(steps[-1]) if steps else 0

    def summary(self):
        """The run's summary (None: none, or not readable)."""
        path = results_path(self.case).with_suffix(".summary.json")
        try:
            return json.loads(path.read_text())
        except (OSError, ValueError):
            return None

    def results_steps(self):
        """Steps in the results file, None if there is none or it cannot be read."""
        path = results_path(self.case)
        if not path.exists():
            return None
        try:
            with ResultsFile(path) as results:
                return len(results.steps)
        except (ResultsFileError, Exception):
            return None


def processes_in(directory):
    """Pids of the processes whose working directory is `directory` or below."""
    directory = os.path.realpath(directory)
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        try:
            cwd = os.readlink(f"/proc/{entry}/cwd")
        except OSError:
            continue
        if cwd == directory or cwd.startswith(directory + "/"):
            found.append(int(entry))
    return found


def orphans(trial):
    time.sleep(0.2)
    end = time.time() + 3.0
    while time.time() < end and processes_in(trial.dir):
        time.sleep(0.1)
    left = processes_in(trial.dir)
    for pid in left:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    return len(left)


CRASH_MARKS = ("terminate called", "Aborted", "AddressSanitizer", "runtime error:",
               "Segmentation fault", "core dumped")


def judge(trial, code, hung, text, killed_coupler=False, expect_completed=False, may_lose=0):
    """The row entries of one trial: clean, crash, hang, orphan, data_lost (0 or 1 each);
    `may_lose`: reported steps that may be missing from the file (a batch not yet written)."""
    result = dict(clean=0, crash=0, hang=0, orphan=0, data_lost=0)
    if hung:
        result["hang"] = 1
    elif not killed_coupler and (code < 0 or any(mark in text for mark in CRASH_MARKS)):
        result["crash"] = 1
    if orphans(trial):
        result["orphan"] = 1
    reported = trial.last_reported_step(text)
    written = trial.results_steps()
    if reported > 0 and (written is None or written < reported - may_lose):
        result["data_lost"] = 1
    # The summary's count of this run's steps in the file (a restart's file holds more).
    counted = (trial.summary() or {}).get("steps_written")
    if counted is not None and (written is None or counted > written):
        result["data_lost"] = 1
    if expect_completed and code != 0:
        result["data_lost"] = 1
    ended_cleanly = killed_coupler or (code in (0, 1, 2, 3) and (code in (0, 3) or "error:" in text))
    if ended_cleanly and not any(result[k] for k in ("crash", "hang", "orphan", "data_lost")):
        result["clean"] = 1
    return result


# Scenarios: each runs one trial and returns its judgement (or None when skipped).

def signal_solver(trial, rng, signals):
    """Sends one of `signals` to the flow or the structure solver at a random moment."""
    trial.start()
    trial.wait_for_step(rng.randint(1, STEPS // 2))
    time.sleep(rng.uniform(0, 0.01))
    pid = trial.solver_pid(rng.choice(["flow", "structure"]))
    if pid:
        os.kill(pid, rng.choice(signals))
    code, hung = trial.wait()
    return judge(trial, code, hung, trial.output())


def solver_kill9(trial, rng):
    return signal_solver(trial, rng, [signal.SIGKILL])


def solver_sigstop(trial, rng):
    return signal_solver(trial, rng, [signal.SIGSTOP])


def solver_signals(trial, rng):
    return signal_solver(trial, rng, [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])


def coupler_signals(trial, rng):
    trial.start()
    trial.wait_for_step(rng.randint(1, STEPS // 2))
    time.sleep(rng.uniform(0, 0.01))
    trial.process.send_signal(rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGHUP]))
    code, hung = trial.wait()
    return judge(trial, code, hung, trial.output())


def coupler_kill9(trial, rng):
    trial.start()
    trial.wait_for_step(rng.randint(1, STEPS // 2))
    time.sleep(rng.uniform(0, 0.01))
    trial.process.kill()
    code, hung = trial.wait()
    return judge(trial, code, hung, trial.output(), killed_coupler=True)


def coupler_kill9_batched(trial, rng):
    """Killed at once with the steps written in batches (results_write_interval 1 s, as the tube
    examples): at most the last batch, BATCH_STEPS steps, may be missing."""
    trial.write_case(case_text(steps=3000, write_interval=1.0))
    trial.start()
    trial.wait_for_step(rng.randint(150, 1500))
    time.sleep(rng.uniform(0, 0.01))
    trial.process.kill()
    code, hung = trial.wait()
    return judge(trial, code, hung, trial.output(), killed_coupler=True, may_lose=BATCH_STEPS)


def coupler_kill9_restart(trial, rng):
    """Killed at a random moment (often inside a flush of the results file) with a state saved
    every 10 steps; `run --restart` must then complete the case."""
    trial.write_case(case_text(state_interval=10))
    trial.start()
    trial.wait_for_step(rng.randint(11, STEPS // 2))
    time.sleep(rng.uniform(0, 0.01))
    trial.process.kill()
    trial.wait()
    if orphans(trial):
        return dict(clean=0, crash=0, hang=0, orphan=1, data_lost=0)
    trial.output_path = os.path.join(trial.dir, "restart.out")
    trial.process = subprocess.Popen([trial.binary, "run", "--restart", trial.case],
                                     stdout=open(trial.output_path, "w"),
                                     stderr=subprocess.STDOUT, start_new_session=True)
    code, hung = trial.wait()
    result = judge(trial, code, hung, trial.output(), expect_completed=True)
    if result["clean"] and trial.results_steps() != STEPS:
        result.update(clean=0, data_lost=1)
    return result


ABUSES = ["garbage_type", "truncated", "huge_length", "wrong_count", "nan", "exit",
          "bad_version", "extra_bytes", "error_flood", "reply_twice"]


_abuse_count = [0]


def protocol_abuse(trial, rng):
    # In turn, so that 10 trials try every abuse once.
    mode = ABUSES[_abuse_count[0] % len(ABUSES)]
    _abuse_count[0] += 1
    fake = os.path.join(ROOT, "scripts", "fault_solver.py")
    fault_flow = {"type": "process", "name": "flow", "working_directory": "flow",
                  "command": ["/usr/bin/python3", fake]}
    trial.write_case(case_text(flow=fault_flow))
    # The fake solver speaks the protocol with the Python SDK's constants.
    sdk = os.path.join(ROOT, "solvers", "sdk")
    trial.start(extra_env={"COCOPP_FAULT": mode, "COCOPP_FAULT_STEP": str(rng.randint(1, 5)),
                           "PYTHONPATH": os.pathsep.join(
                               filter(None, [sdk, os.environ.get("PYTHONPATH")]))})
    code, hung = trial.wait()
    text = trial.output()
    result = judge(trial, code, hung, text)
    if code != 1 or len(text) > 200_000:  # every abuse is an error, and its text is bounded
        result["clean"] = 0
    return result


def concurrent_runs(trial, rng):
    trial.write_case(case_text(steps=2000))
    trial.start("first")
    trial.wait_for_step(rng.randint(1, 100))
    second = subprocess.run([trial.binary, "run", trial.case], capture_output=True, text=True,
                            timeout=HANG_LIMIT)
    code, hung = trial.wait()
    result = judge(trial, code, hung, trial.output(), expect_completed=True)
    if second.returncode != 1 or "another cocopp run" not in second.stderr:
        result["clean"] = 0
    return result


LINKS = ["results/case.h5", "results/case.state.h5.writing", "flow/flow.log",
         "flow/to_solver_00000001.tmp"]


def planted_links(trial, rng):
    where = rng.choice(LINKS)
    target = os.path.join(trial.dir, "precious.txt")
    with open(target, "w") as f:
        f.write("keep me\n")
    transport = "file" if "to_solver" in where else "pipe"
    trial.write_case(case_text(steps=20, transport=transport))
    os.makedirs(os.path.dirname(os.path.join(trial.dir, where)), exist_ok=True)
    os.symlink(target, os.path.join(trial.dir, where))
    trial.start()
    code, hung = trial.wait()
    result = judge(trial, code, hung, trial.output())
    with open(target) as f:
        if f.read() != "keep me\n":
            result["data_lost"] = 1
            result["clean"] = 0
    return result


def disk_full(trial, rng):
    results = os.path.join(trial.dir, "results")
    os.makedirs(results)
    size = rng.choice([512, 1024, 2048])  # KiB: room for some steps, then full
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}k", "tmpfs", results],
                             capture_output=True)
    if mounted.returncode != 0:
        return None  # not root, or no mount here: skipped
    try:
        # Written step by step, or in batches of up to a second (BATCH_STEPS steps): a batch
        # that does not fit is written as far as it fits, and the summary says how far.
        batched = rng.random() < 0.5
        trial.write_case(case_text(steps=2000, write_interval=1.0 if batched else 0.0))
        trial.start()
        code, hung = trial.wait()
        text = trial.output()
        result = judge(trial, code, hung, text, may_lose=BATCH_STEPS if batched else 0)
        written = trial.results_steps()
        if not written or (trial.summary() or {}).get("steps_written") != written:
            result["data_lost"], result["clean"] = 1, 0  # a batch dropped whole, or miscounted
        return result
    finally:
        subprocess.run(["umount", "-l", results], capture_output=True)


SCENARIOS = {
    "solver_kill9": solver_kill9,
    "solver_sigstop": solver_sigstop,
    "solver_signals": solver_signals,
    "coupler_signals": coupler_signals,
    "coupler_kill9": coupler_kill9,
    "coupler_kill9_restart": coupler_kill9_restart,
    "coupler_kill9_batched": coupler_kill9_batched,
    "protocol_abuse": protocol_abuse,
    "concurrent_runs": concurrent_runs,
    "planted_links": planted_links,
    "disk_full": disk_full,
}
DEFAULT = list(SCENARIOS)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", help="directory of the built cocopp (default: the one "
                                       "cocopp.executable finds, e.g. build/bin)")
    parser.add_argument("--trials", type=int, default=10, help="trials per scenario (10)")
    parser.add_argument("--scenarios", default=",".join(DEFAULT),
                        help="comma-separated, of: " + ", ".join(SCENARIOS) +
                        " (default: all; disk_full needs root for its tmpfs, else it is skipped)")
    parser.add_argument("--seed", type=int, default=1, help="random seed (1)")
    parser.add_argument("--keep", action="store_true", help="keep the trial directories")
    args = parser.parse_args()
    binary = os.path.join(args.bin, "cocopp") if args.bin else str(find_cocopp())
    if not os.access(binary, os.X_OK):
        sys.exit(f"fault_injection: no cocopp at {binary} (build first, or give --bin)")
    names = [n.strip() for n in args.scenarios.split(",") if n.strip()]
    unknown = [n for n in names if n not in SCENARIOS]
    if unknown:
        sys.exit(f"fault_injection: unknown scenarios {unknown}; known: {list(SCENARIOS)}")
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="cocopp_faults_")
    columns = ["clean", "crash", "hang", "orphan", "data_lost"]
    print(f"{'scenario':<22} {'trials':>6} " + " ".join(f"{c:>9}" for c in columns))
    bad = 0
    for name in names:
        totals = dict.fromkeys(columns, 0)
        trials = 0
        for _ in range(args.trials):
            trial = Trial(work, name, binary)
            result = SCENARIOS[name](trial, rng)
            if result is None:
                continue
            trials += 1
            for c in columns:
                totals[c] += result[c]
            if any(result[c] for c in columns[1:]) or not result["clean"]:
                print(f"  {name}: see {trial.dir}", file=sys.stderr)
                args.keep = True
        if trials == 0:
            print(f"{name:<22} {'skipped (needs root for a tmpfs mount)':>40}")
            continue
        bad += sum(totals[c] for c in columns[1:]) + (trials - totals["clean"])
        print(f"{name:<22} {trials:>6} " + " ".join(f"{totals[c]:>9}" for c in columns))
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
