#!/usr/bin/python3
"""docs/tutorial.md, run as a reader would, ctest `tutorial`: every ```sh block is run in order
in one shell session (its environment and directory carried from block to block), every
```<language> file=PATH block is written to PATH first, and every line of a ```text expect
block must appear in the output of the sh block before it. HOME is a temporary directory, and
the session starts in a directory whose `build` is the build tree, as in a cocopp checkout.

usage: test_tutorial.py BUILD_DIR SOURCE_DIR
"""
import os
import re
import subprocess
import sys
import tempfile

FENCE = re.compile(r"^```(\S*)(.*)$")


def blocks(markdown):
    """[(language, info, text, line)] of the fenced blocks."""
    found, inside = [], None
    for number, line in enumerate(markdown.splitlines(), 1):
        match = FENCE.match(line)
        if inside is None and match and match.group(1):
            inside = (match.group(1), match.group(2).strip(), [], number)
        elif inside is not None and line.startswith("```"):
            found.append((inside[0], inside[1], "\n".join(inside[2]) + "\n", inside[3]))
            inside = None
        elif inside is not None:
            inside[2].append(line)
    return found


def main():
    build, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    tutorial = os.path.join(source, "docs", "tutorial.md")
    with open(tutorial) as f:
        steps = blocks(f.read())
    with tempfile.TemporaryDirectory(prefix="cocopp-tutorial-") as scratch:
        home = os.path.join(scratch, "home")
        checkout = os.path.join(scratch, "checkout")
        os.makedirs(home)
        os.makedirs(checkout)
        os.symlink(build, os.path.join(checkout, "build"))
        state = os.path.join(scratch, "state.sh")
        env = {key: value for key, value in os.environ.items() if not key.startswith("COCOPP_")}
        env.update(HOME=home, PATH="/usr/bin:/bin:" + env.get("PATH", ""))
        with open(state, "w") as f:
            f.write(f"cd {checkout}\n")
        output, ran, written, expected = "", 0, 0, 0
        for language, info, text, line in steps:
            where = f"docs/tutorial.md:{line}"
            if info.startswith("file="):
                path = os.path.expanduser(info[len("file="):].replace("~", home, 1))
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "w") as f:
                    f.write(text)
                written += 1
            elif language == "sh":
                script = (f"source {state}\nset -euo pipefail\n{text}\n"
                          f"export -p > {state}.new\necho \"cd $(pwd)\" >> {state}.new\n"
                          f"mv {state}.new {state}\n")
                result = subprocess.run(["bash", "-c", script], env=env, stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, text=True)
                output = result.stdout
                if result.returncode != 0:
                    sys.exit(f"FAILED: {where}: the commands exited with {result.returncode}:\n"
                             f"{text}\n--- output ---\n{output}")
                print(f"ok: {where}: {text.strip().splitlines()[-1]}")
                ran += 1
            elif language == "text" and info == "expect":
                for wanted in filter(None, (line.strip() for line in text.splitlines())):
                    if wanted not in output:
                        sys.exit(f"FAILED: {where}: '{wanted}' is not in the output of the "
                                 f"commands before it:\n{output}")
                    expected += 1
        if ran == 0 or written == 0:
            sys.exit("FAILED: the tutorial has no commands or no files")
    print(f"tutorial: {ran} command blocks run, {written} files written, {expected} expected "
          "lines found")


if __name__ == "__main__":
    main()
