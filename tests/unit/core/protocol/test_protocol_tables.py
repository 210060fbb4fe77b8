#!/usr/bin/env python3
"""The protocol's constants and the variable table are written three times: in C++
(core/protocol, which cocopp-protocol-table prints), in the Python SDK (solvers/sdk/cocopp_sdk.py,
which scripts/fault_solver.py takes them from) and in docs/protocol.md. This test holds the
other two to the C++ side, so that a variable or a message type added in one place only fails
CI; it also plants such a difference to show that it is found.

usage: test_protocol_tables.py BIN_DIR SOURCE_DIR   (ctest protocol_tables)
"""
import copy
import json
import os
import re
import subprocess
import sys


def cpp_tables(bin_dir):
    output = subprocess.run([os.path.join(bin_dir, "cocopp-protocol-table")], check=True,
                            capture_output=True, text=True).stdout
    return json.loads(output)


def python_tables(source):
    sys.path.insert(0, os.path.join(source, "solvers", "sdk"))
    import cocopp_sdk
    return {"protocol_version": cocopp_sdk.PROTOCOL_VERSION,
            "max_payload": cocopp_sdk.MAX_PAYLOAD,
            "message_types": dict(cocopp_sdk.MESSAGE_TYPES),
            "components": dict(cocopp_sdk.VARIABLE_COMPONENTS)}


def docs_tables(source):
    with open(os.path.join(source, "docs", "protocol.md"), encoding="utf-8") as f:
        text = f.read()
    # "| 3 | `SOLVE` | → solver | ..." rows of the message table
    types = {name: int(number) for number, name in re.findall(r"^\| (\d+) \| `(\w+)` \|", text,
                                                                re.M)}
    # "Variables and their components per point: `displacement` 3, `pressure` 1, ..."
    paragraph = text[text.index("Variables and their components per point:"):]
    paragraph = paragraph[:paragraph.index("\n\n")]
    components = {name: int(count) for name, count in re.findall(r"`(\w+)` (\d)", paragraph)}
    version = int(re.search(r"protocol version u32 \(= (\d+)\)", text).group(1))
    return {"protocol_version": version, "message_types": types, "components": components}


def differences(cpp, other, where):
    """What `other` (the Python SDK's or the docs' tables) says differently from the C++ side."""
    found = []
    components = {name: v["components"] for name, v in cpp["variables"].items()}
    for key, reference in (("protocol_version", cpp["protocol_version"]),
                           ("max_payload", cpp["max_payload"]),
                           ("message_types", cpp["message_types"]),
                           ("components", components)):
        if key not in other or other[key] == reference:
            continue
        if isinstance(reference, dict):
            for name in sorted(set(reference) | set(other[key])):
                if reference.get(name) != other[key].get(name):
                    found.append(f"{where}: {key} '{name}' is {other[key].get(name)}, "
                                 f"the C++ side says {reference.get(name)}")
        else:
            found.append(f"{where}: {key} is {other[key]}, the C++ side says {reference}")
    return found


def main(bin_dir, source):
    cpp = cpp_tables(bin_dir)
    problems = (differences(cpp, python_tables(source), "solvers/sdk/cocopp_sdk.py")
                + differences(cpp, docs_tables(source), "docs/protocol.md"))
    for problem in problems:
        print("FAIL " + problem)
    # The check itself: a variable in C++ only, and a message type renumbered, are found.
    planted = copy.deepcopy(cpp)
    planted["variables"]["stress"] = {"components": 6, "unit": "Pa"}
    planted["message_types"]["SOLVE"] = 9
    found = differences(planted, python_tables(source), "sdk")
    planted_found = (any("'stress' is None" in line for line in found)
                     and any("'SOLVE' is 3, the C++ side says 9" in line for line in found))
    if not planted_found:
        print("FAIL a planted difference is not reported: " + "; ".join(found))
    counts = f"{len(cpp['variables'])} variables, {len(cpp['message_types'])} message types"
    if problems or not planted_found:
        return 1
    print(f"protocol_tables: the Python SDK and docs/protocol.md agree with C++ ({counts})")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
