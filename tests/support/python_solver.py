#!/usr/bin/env python3
"""A cocopp solver written without the SDK, to show the protocol from another language
(docs/protocol.md); the tests run it. Pipe transport only.

One model part `wall` of 3 points on the x axis; input displacement, output
pressure_i = 1000 * y-displacement_i + step.
"""
import os
import struct
import sys

# Message types (the first byte of every frame).
INITIALIZE, INITIALIZE_STEP, SOLVE, FINALIZE_STEP, OUTPUT_STEP, STOP = 1, 2, 3, 4, 5, 6
SAVE_RESTART = 7
HELLO, OK, INTERFACE, DATA, ERROR = 128, 129, 130, 131, 132
PROTOCOL_VERSION = 1
POINTS = 3

channel = os.environ.get("COCOPP_CHANNEL")
if os.environ.get("COCOPP_TRANSPORT") != "pipe" or not channel:
    sys.exit("this program is a cocopp solver; run it through `cocopp run case.yaml`")

# Blocking opens are fine on the solver side, in this order or the other.
requests = open(os.path.join(channel, "cocopp_to_solver.fifo"), "rb", buffering=0)
replies = open(os.path.join(channel, "cocopp_from_solver.fifo"), "wb", buffering=0)


def read_exactly(size):
    data = b""
    while len(data) < size:
        chunk = requests.read(size - len(data))
        if not chunk:
            sys.exit("the coupler closed the pipe")
        data += chunk
    return data


def receive():
    (length,) = struct.unpack("<I", read_exactly(4))
    return read_exactly(length)


def send(payload):
    replies.write(struct.pack("<I", len(payload)) + payload)


def string(text):
    data = text.encode()
    return struct.pack("<I", len(data)) + data


def f64_array(values):
    return struct.pack(f"<Q{len(values)}d", len(values), *values)


def i64_array(values):
    return struct.pack(f"<Q{len(values)}q", len(values), *values)


def names(items):
    return struct.pack("<I", len(items)) + b"".join(string(item) for item in items)


def interface():
    coordinates = [c for i in range(POINTS) for c in (0.1 * i, 0.0, 0.0)]
    return (struct.pack("<BI", INTERFACE, 1) + string("wall")
            + i64_array(list(range(1, POINTS + 1))) + f64_array(coordinates)
            + names(["displacement"]) + names(["pressure"])
            + f64_array([]))  # no initial output: zeros


send(struct.pack("<BIq", HELLO, PROTOCOL_VERSION, os.getpid()))
step = 0
while True:
    request = receive()
    kind = request[0]
    if kind == INITIALIZE:
        delta_t, timestep_start = struct.unpack_from("<di", request, 1)
        send(interface())
    elif kind == INITIALIZE_STEP:
        step, time = struct.unpack_from("<id", request, 1)
        send(bytes([OK]))
    elif kind == SOLVE:
        (count,) = struct.unpack_from("<Q", request, 1)
        displacement = struct.unpack_from(f"<{count}d", request, 9)
        send(bytes([DATA]) + f64_array(
            [1000.0 * displacement[3 * i + 1] + step for i in range(POINTS)]))
    elif kind in (FINALIZE_STEP, OUTPUT_STEP):
        send(bytes([OK]))
    elif kind == SAVE_RESTART:
        send(bytes([OK]))  # its output depends on the step only: nothing to keep
    elif kind == STOP:
        send(bytes([OK]))
        sys.exit(0)
    else:
        send(bytes([ERROR]) + string(f"unexpected request type {kind}"))
        sys.exit(1)
