#!/usr/bin/env python3
"""A cocopp solver that misbehaves on purpose, for scripts/fault_injection.py.

It speaks the protocol (docs/protocol.md) as the tube flow solver would (model part `wall`,
displacement in, pressure and traction out) and breaks it at a chosen point, given by the
environment variable COCOPP_FAULT (the mode) and COCOPP_FAULT_STEP (the step, default 3):

  garbage_type    replies to SOLVE with a frame of an unknown type
  truncated       replies with a DATA frame shorter than its length prefix says, then waits
  huge_length     announces a 1 GiB frame and sends nothing more
  wrong_count     replies with DATA of one value too many
  nan             replies with NaN pressures
  exit            exits with code 7 in the middle of a step
  bad_version     says HELLO with protocol version 99
  extra_bytes     replies with a DATA frame followed by bytes that belong to no frame
  error_flood     replies with an ERROR of 50 MB with escape sequences
  reply_twice     replies to FINALIZE_STEP with OK twice
  none            behaves (a control)
Pipe transport only. The message types and the protocol version are the Python SDK's
(cocopp_sdk, on PYTHONPATH: scripts/fault_injection.py puts solvers/sdk there).
"""
import math
import os
import struct
import sys

from cocopp_sdk import MESSAGE_TYPES, PROTOCOL_VERSION

(INITIALIZE, INITIALIZE_STEP, SOLVE, FINALIZE_STEP, OUTPUT_STEP, STOP, SAVE_RESTART, HELLO, OK,
 INTERFACE, DATA, ERROR) = (MESSAGE_TYPES[name] for name in (
     "INITIALIZE", "INITIALIZE_STEP", "SOLVE", "FINALIZE_STEP", "OUTPUT_STEP", "STOP",
     "SAVE_RESTART", "HELLO", "OK", "INTERFACE", "DATA", "ERROR"))
POINTS = 100

mode = os.environ.get("COCOPP_FAULT", "none")
fault_step = int(os.environ.get("COCOPP_FAULT_STEP", "3"))
channel = os.environ.get("COCOPP_CHANNEL")
if os.environ.get("COCOPP_TRANSPORT") != "pipe" or not channel:
    sys.exit("this program is a cocopp solver; run it through `cocopp run case.yaml`")
requests = open(os.path.join(channel, "cocopp_to_solver.fifo"), "rb", buffering=0)
replies = open(os.path.join(channel, "cocopp_from_solver.fifo"), "wb", buffering=0)


def read_exactly(size):
    data = b""
    while len(data) < size:
        chunk = requests.read(size - len(data))
        if not chunk:
            sys.exit(0)
        data += chunk
    return data


def receive():
    (length,) = struct.unpack("<I", read_exactly(4))
    return read_exactly(length)


def send(payload, raw_suffix=b""):
    replies.write(struct.pack("<I", len(payload)) + payload + raw_suffix)


def string(text):
    data = text.encode()
    return struct.pack("<I", len(data)) + data


def f64_array(values):
    return struct.pack(f"<Q{len(values)}d", len(values), *values)


def interface():
    ids = list(range(POINTS))
    coordinates = [c for i in ids for c in (0.0, 0.005, -0.025 + 0.05 * (i + 0.5) / POINTS)]
    names = lambda items: struct.pack("<I", len(items)) + b"".join(string(i) for i in items)
    return (struct.pack("<BI", INTERFACE, 1) + string("wall")
            + struct.pack(f"<Q{POINTS}q", POINTS, *ids) + f64_array(coordinates)
            + names(["displacement"]) + names(["pressure", "traction"]) + f64_array([]))


def data(displacement, step):
    pressure = [1e6 * displacement[3 * i + 1] + step for i in range(POINTS)]
    return bytes([DATA]) + f64_array(pressure + [0.0] * (3 * POINTS))


send(struct.pack("<BIq", HELLO, 99 if mode == "bad_version" else PROTOCOL_VERSION, os.getpid()))
step = 0
while True:
    request = receive()
    kind = request[0]
    faulty = step == fault_step
    if kind == INITIALIZE:
        send(interface())
    elif kind == INITIALIZE_STEP:
        step = struct.unpack_from("<i", request, 1)[0]
        send(bytes([OK]))
    elif kind == SOLVE:
        (count,) = struct.unpack_from("<Q", request, 1)
        displacement = struct.unpack_from(f"<{count}d", request, 9)
        reply = data(displacement, step)
        if faulty and mode == "garbage_type":
            send(bytes([77]) + reply[1:])
        elif faulty and mode == "truncated":
            replies.write(struct.pack("<I", len(reply)) + reply[: len(reply) // 2])
            while True:
                read_exactly(1)
        elif faulty and mode == "huge_length":
            replies.write(struct.pack("<I", 1 << 30))
            while True:
                read_exactly(1)
        elif faulty and mode == "wrong_count":
            send(bytes([DATA]) + f64_array([0.0] * (4 * POINTS + 1)))
        elif faulty and mode == "nan":
            send(bytes([DATA]) + f64_array([math.nan] * (4 * POINTS)))
        elif faulty and mode == "exit":
            sys.exit(7)
        elif faulty and mode == "extra_bytes":
            send(reply, raw_suffix=b"\x01\x02\x03")
        elif faulty and mode == "error_flood":
            send(bytes([ERROR]) + string("\x1b[2J flood " + "x" * (50 << 20)))
            sys.exit(1)
        else:
            send(reply)
    elif kind == FINALIZE_STEP:
        send(bytes([OK]))
        if faulty and mode == "reply_twice":
            send(bytes([OK]))
    elif kind in (OUTPUT_STEP, SAVE_RESTART):
        send(bytes([OK]))
    elif kind == STOP:
        send(bytes([OK]))
        sys.exit(0)
    else:
        send(bytes([ERROR]) + string(f"unexpected request type {kind}"))
        sys.exit(1)
