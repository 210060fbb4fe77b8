#!/usr/bin/python3
"""Docs that cannot drift, ctest doc_commands:

1. every command shown in README.md and docs/*.md (shell lines of the untyped and sh code
   blocks, and `$ ` lines of text blocks) is listed in tests/docs/doc_commands.yaml with how CI
   proves it, and every entry there is still shown somewhere;
2. the entries marked `run: true` are run as shown, in order, from the root of a copy of the
   checkout (README, docs, examples, scripts and the package python/; `build` is the build
   tree), with the build's cocopp first on PATH and the copy's python/ on PYTHONPATH (where
   scripts/build.sh's .pth file puts a checkout's); each must succeed;
3. the sample outputs in the docs match the fresh runs: README's progress lines (iterations
   exactly, residuals within 1 %) and summary, and docs/bench.md's table (status, steps and
   iteration counts exactly, errors within 5 %; times are the machine's).

docs/tutorial.md is run whole by ctest tutorial. usage: test_doc_commands.py BIN_DIR SOURCE_DIR
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

import yaml

PROGRAMS = {"cocopp", "cmake", "cpack", "ctest", "apt-get", "cp", "paraview", "g++", "cgx",
            "foamToVTK", "reconstructPar", "/usr/bin/python3", "python3"}


def check(condition, message):
    if not condition:
        sys.exit(f"FAILED: {message}")
    print(f"ok: {message}")


def normalize(command):
    """One line, no trailing comment, single spaces."""
    command = re.sub(r"\s+#.*$", "", command.strip())
    return " ".join(command.split())


def is_command(line, source):
    try:
        words = shlex.split(line, comments=True)  # VAR="a b" is one word
    except ValueError:
        words = line.split()
    if not words:
        return False
    first = next((w for w in words if "=" not in w), "")  # after VAR=value assignments
    return first in PROGRAMS or (("/" in first) and os.path.isfile(os.path.join(source, first))) \
        or first == "build/bin/cocopp"


def documented_commands(source):
    """{normalized command: first place shown}"""
    found = {}
    files = [os.path.join(source, "README.md")] + sorted(glob.glob(os.path.join(source, "docs",
                                                                                "*.md")))
    for path in files:
        if path.endswith("tutorial.md"):
            continue
        language, pending = None, ""
        with open(path) as f:
            for number, line in enumerate(f, 1):
                if line.startswith("```"):
                    language = line[3:].strip().split(" ")[0] if language is None else None
                    continue
                if language is None:
                    continue
                text = pending + line.rstrip("\n")
                if text.endswith("\\"):  # a continued line
                    pending = text[:-1] + " "
                    continue
                pending = ""
                if language == "text":
                    if text.startswith("$ "):
                        found.setdefault(normalize(text[2:]),
                                         f"{os.path.relpath(path, source)}:{number}")
                elif language in ("", "sh", "bash") and is_command(text.strip(), source):
                    found.setdefault(normalize(text), f"{os.path.relpath(path, source)}:{number}")
    return found


def tracked_files(source, parts):
    """The files of `parts` that git tracks (what a fresh checkout has, without the products of
    earlier runs)."""
    listed = subprocess.run(["git", "-C", source, "ls-files", "--", *parts],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if listed.returncode != 0 or not listed.stdout.strip():
        sys.exit(f"FAILED: cannot list the checkout's files with git: {listed.stderr}")
    return listed.stdout.splitlines()


def doc_block(path, first_line):
    """The lines of the fenced block whose first line starts with `first_line`."""
    with open(path) as f:
        text = f.read()
    for block in re.findall(r"```[^\n]*\n(.*?)```", text, re.S):
        if block.startswith(first_line):
            return block.splitlines()
    sys.exit(f"FAILED: no block starting with '{first_line}' in {path}")


def compare_progress(documented, output):
    """README's progress lines against a fresh run's."""
    step = re.compile(r"^step +(\d+) / \d+ .* iterations +(\d+) +residual ([0-9.e+-]+)")
    fresh = {}
    for line in output.splitlines():
        match = step.match(line)
        if match:
            fresh[int(match.group(1))] = (int(match.group(2)), float(match.group(3)))
    compared = 0
    for line in documented:
        match = step.match(line)
        if not match:
            continue
        number, iterations, residual = int(match.group(1)), int(match.group(2)), float(
            match.group(3))
        check(number in fresh and fresh[number][0] == iterations
              and abs(fresh[number][1] - residual) <= 0.01 * residual,
              f"README step {number}: {iterations} iterations, residual {residual:.3e} "
              f"(fresh run: {fresh.get(number)})")
        compared += 1
    summary = [line.strip() for line in documented if line.strip().startswith("iterations ")]
    check(len(summary) == 1 and summary[0] in output,
          f"README summary '{summary[0] if summary else ''}' as the fresh run prints it")
    return compared


def compare_bench_table(documented, output):
    """docs/bench.md's table against a fresh bench's, row by row (times left out)."""
    def rows(lines):
        """{variant: [variant, solver, status, steps, avg it, max it, calls, wall, coupler,
        displ err, press err]}"""
        table = {}
        for line in lines:
            words = line.split()
            if len(words) > 3 and words[2] == "stalled":
                words[2:4] = [" ".join(words[2:4])]  # 'stalled 2' is one column
            if len(words) == 11 and words[0] != "variant" and not line.startswith(" "):
                table[words[0]] = words
        return table

    fresh = rows(output.splitlines())
    shown = rows(documented)
    check(len(shown) >= 5, f"docs/bench.md's table has {len(shown)} rows")
    for name, words in shown.items():
        got = fresh.get(name)
        check(got is not None, f"bench.md row {name} is in the fresh bench")
        same = words[1:7] == got[1:7]  # solver, status, steps, avg it, max it, calls

        def close(a, b):
            if a == "-" or b == "-":
                return a == b
            a, b = float(a), float(b)
            return abs(a - b) <= 0.05 * max(abs(a), abs(b)) or a == b

        check(same and close(words[9], got[9]) and close(words[10], got[10]),
              f"bench.md row {name}: {' '.join(words[1:7])}, errors {words[9]} {words[10]} "
              f"(fresh: {' '.join(got[1:7])}, {got[9]} {got[10]})")


def main():
    bin_dir, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with open(os.path.join(source, "tests", "docs", "doc_commands.yaml")) as f:
        registry = yaml.safe_load(f)
    listed = {normalize(entry["command"]): entry for entry in registry}
    shown = documented_commands(source)
    unlisted = [f"{where}: {command}" for command, where in shown.items() if command not in listed]
    check(not unlisted, "every documented command is in tests/docs/doc_commands.yaml"
          + ("".join(f"\n  missing: {u}" for u in unlisted)))
    stale = [command for command in listed if command not in shown]
    check(not stale, "every entry of doc_commands.yaml is still shown in the docs"
          + "".join(f"\n  stale: {s}" for s in stale))
    for command, entry in listed.items():
        ways = [key for key in ("run", "tested_by", "not_run") if entry.get(key)]
        check(len(ways) == 1, f"'{command}' says how CI covers it, once ({ways})")

    # Run them, in order, as a user in a checkout would: in a copy, so that the runs leave
    # nothing in the examples other tests copy.
    env = {key: value for key, value in os.environ.items() if not key.startswith("COCOPP_")}
    env["PATH"] = f"{bin_dir}:/usr/bin:/bin:{env.get('PATH', '')}"
    outputs = {}
    with tempfile.TemporaryDirectory(prefix="cocopp-doc-commands-") as checkout:
        env["PYTHONPATH"] = os.path.join(checkout, "python")
        for path in tracked_files(source, ("README.md", "bench", "docs", "examples", "scripts",
                                           "python", "solvers/sdk")):  # the Python SDK
            os.makedirs(os.path.join(checkout, os.path.dirname(path)), exist_ok=True)
            shutil.copy2(os.path.join(source, path), os.path.join(checkout, path))
        os.symlink(os.path.dirname(bin_dir), os.path.join(checkout, "build"))
        for command, entry in listed.items():
            if not entry.get("run"):
                continue
            result = subprocess.run(["bash", "-c", command], cwd=checkout, env=env,
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            check(result.returncode == 0, f"ran: {command}"
                  + ("" if result.returncode == 0 else f"\n{result.stdout[-3000:]}"))
            outputs[command] = result.stdout

    readme = doc_block(os.path.join(source, "README.md"), "cocopp 0.1.0: case")
    count = compare_progress(readme, outputs["cocopp run examples/tube/flow_structure/case.yaml"])
    check(count >= 3, f"README: {count} progress lines compared")
    compare_bench_table(doc_block(os.path.join(source, "docs", "bench.md"), "$ cocopp bench"),
                        outputs["cocopp bench examples/tube/bench/bench.yaml"])
    print(f"doc_commands: {len(shown)} documented commands, "
          f"{sum(1 for e in listed.values() if e.get('run'))} run")


if __name__ == "__main__":
    main()
