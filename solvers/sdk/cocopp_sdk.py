"""cocopp solver SDK for Python: a solver written in Python, driven by the cocopp coupler.

The Python twin of the C++ SDK (solvers/sdk/solver_sdk.hpp, docs/protocol.md): derive
from Solver, return the interface from initialize(), map input to output in solve(), and call
serve(). The SDK speaks the protocol (pipe, file and TCP transport), checks what the solver returns
and turns exceptions into messages the coupler shows. Interface data are NumPy arrays.

    import sys
    import numpy as np
    import cocopp_sdk as sdk

    class Wall(sdk.Solver):
        def initialize(self, run):
            points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
            wall = sdk.ModelPart("wall", ids=[1, 2], coordinates=points,
                                 inputs=["displacement"], outputs=["pressure"])
            return sdk.Interface([wall])

        def solve(self, values):
            displacement = self.interface.split_input(values)["wall", "displacement"]
            return 1000.0 * displacement[:, 1]

    if __name__ == "__main__":
        sys.exit(sdk.serve(Wall()))

Run it through `cocopp run case.yaml` with a solver of type `process` whose command starts it
(`command: [python3, wall.py]`). Needs Python 3.7 and NumPy.
"""
import os
import socket
import struct
import sys
import time

import numpy as np

__all__ = ["ModelPart", "Interface", "RunInfo", "Solver", "InputRejected", "ProtocolError",
           "serve", "wants_help", "VARIABLE_COMPONENTS", "PROTOCOL_VERSION", "MESSAGE_TYPES",
           "MAX_PAYLOAD"]

# The protocol's constants and the variable table, as the C++ side defines them
# (core/protocol/messages.hpp, frame.hpp, variable_components.cpp); ctest protocol_tables
# compares them with it and with docs/protocol.md.
PROTOCOL_VERSION = 1
# Variables and their components per point.
VARIABLE_COMPONENTS = {"displacement": 3, "pressure": 1, "traction": 3, "force": 3,
                       "velocity": 3, "temperature": 1, "heat_flux": 1, "gap": 1,
                       "wall_displacement": 3, "coverage": 1, "driven": 1}
# Message types, the first byte of every frame (docs/protocol.md, section 3): requests below
# 128, replies from 128.
MESSAGE_TYPES = {"INITIALIZE": 1, "INITIALIZE_STEP": 2, "SOLVE": 3, "FINALIZE_STEP": 4,
                 "OUTPUT_STEP": 5, "STOP": 6, "SAVE_RESTART": 7, "REPORT_CONVERGENCE": 8,
                 "SUBSTEPS": 9, "HELLO": 128, "OK": 129, "INTERFACE": 130, "DATA": 131, "ERROR": 132,
                 "REJECTED": 133, "DATA_CONVERGED": 134}
# The longest frame payload either side accepts, in bytes.
MAX_PAYLOAD = 1 << 30

(_INITIALIZE, _INITIALIZE_STEP, _SOLVE, _FINALIZE_STEP, _OUTPUT_STEP, _STOP, _SAVE_RESTART,
 _REPORT_CONVERGENCE, _SUBSTEPS, _HELLO, _OK, _INTERFACE, _DATA, _ERROR, _REJECTED,
 _DATA_CONVERGED) = MESSAGE_TYPES.values()  # in MESSAGE_TYPES' order
_REQUEST_NAMES = {number: name for name, number in MESSAGE_TYPES.items() if number < 128}


class InputRejected(Exception):
    """Raised by Solver.solve() when the solver cannot solve the time step for this input (a mesh
    it would turn inside out) but still holds the step's start: the coupler is told (REJECTED),
    may step back and call solve() again. Any other exception ends the solver."""


class ProtocolError(Exception):
    """A frame that breaks the protocol, or a lost connection."""


class RunInfo:
    """What the coupler sends with INITIALIZE."""

    def __init__(self, delta_t, timestep_start):
        self.delta_t = delta_t
        self.timestep_start = timestep_start

    def __repr__(self):
        return f"RunInfo(delta_t={self.delta_t!r}, timestep_start={self.timestep_start!r})"


class ModelPart:
    """A named set of interface points with the variables the solver takes and gives there.

    ids: integer point ids; coordinates: the initial coordinates, one row (x, y, z) per point;
    inputs, outputs: variable names, e.g. ["displacement"] and ["pressure", "traction"]."""

    def __init__(self, name, ids, coordinates, inputs=(), outputs=()):
        self.name = str(name)
        self.ids = np.asarray(ids, dtype=np.int64).reshape(-1)
        self.coordinates = np.asarray(coordinates, dtype=np.float64)
        self.inputs = list(inputs)
        self.outputs = list(outputs)
        if not self.name:
            raise ValueError("a model part has no name")
        if self.coordinates.size != 3 * self.ids.size:
            raise ValueError(f"model part '{self.name}' has {self.ids.size} ids but "
                             f"{self.coordinates.size} coordinates (3 per point expected)")
        self.coordinates = self.coordinates.reshape(-1, 3)
        for variable in self.inputs + self.outputs:
            if variable not in VARIABLE_COMPONENTS:
                raise ValueError(f"model part '{self.name}': unknown interface variable "
                                 f"'{variable}' (known: {', '.join(VARIABLE_COMPONENTS)})")

    def size(self, variables):
        return sum(self.ids.size * VARIABLE_COMPONENTS[v] for v in variables)


class Interface:
    """The solver's interface: its model parts, in order, and its initial output (None: zeros).

    The data layout of SOLVE's input and of solve()'s output: for each model part in order, for
    each of its input (output) variables in order, all points, the components of a point
    contiguous. split_input() and join_output() convert between that layout and arrays of shape
    (points, components), keyed by (model part, variable)."""

    def __init__(self, model_parts, initial_output=None):
        self.model_parts = list(model_parts)
        names = [part.name for part in self.model_parts]
        for name in names:
            if names.count(name) > 1:
                raise ValueError(f"model part '{name}' is described twice")
        self.input_size = sum(part.size(part.inputs) for part in self.model_parts)
        self.output_size = sum(part.size(part.outputs) for part in self.model_parts)
        self.initial_output = None
        if initial_output is not None and np.size(initial_output) > 0:
            self.initial_output = _vector(initial_output, self.output_size, "initial_output",
                                          "or None for zeros")

    def _blocks(self, which):
        offset = 0
        for part in self.model_parts:
            for variable in getattr(part, which):
                size = part.ids.size * VARIABLE_COMPONENTS[variable]
                yield (part.name, variable), offset, part.ids.size, VARIABLE_COMPONENTS[variable]
                offset += size

    def split_input(self, values):
        """The input vector as {(part, variable): array of shape (points, components)} (views)."""
        values = np.asarray(values, dtype=np.float64)
        return {key: values[offset:offset + points * components].reshape(points, components)
                for key, offset, points, components in self._blocks("inputs")}

    def join_output(self, arrays):
        """The output vector from {(part, variable): array of (points, components) values}."""
        output = np.empty(self.output_size)
        for key, offset, points, components in self._blocks("outputs"):
            if key not in arrays:
                raise ValueError(f"join_output: no values for {key[1]} on model part '{key[0]}'")
            block = np.asarray(arrays[key], dtype=np.float64)
            if block.size != points * components:
                raise ValueError(f"join_output: {key[1]} on model part '{key[0]}' has "
                                 f"{block.size} values; {points} points x {components} expected")
            output[offset:offset + block.size] = block.reshape(-1)
        return output


class Solver:
    """Derive from this and implement initialize() and solve(); the rest is optional.

    Every solve() of a step starts from the state of the last finalize_step() (or the initial
    state): the coupler iterates on the input until the step converges. serve() sets
    self.interface to what initialize() returned."""

    interface = None

    def initialize(self, run):
        """run: RunInfo. Returns the Interface."""
        raise NotImplementedError("the solver must implement initialize(run)")

    def initialize_step(self, step, time):
        pass

    def solve(self, values):
        """One coupling iteration: input values (a flat NumPy array) -> output values."""
        raise NotImplementedError("the solver must implement solve(values)")

    def finalize_step(self):
        pass

    def output_step(self):
        pass

    def finalize(self):
        pass

    def can_restart(self):
        """True if save_restart(step) writes what initialize() with run.timestep_start > 0
        reads back; a solver that returns False is never asked to save."""
        return False

    def save_restart(self, step):
        pass

    def start_reporting_convergence(self):
        """Solver-coupling convergence (the coupler's solver_coupling_convergence criterion):
        called once, before the first step, when the case asks. From then on the coupler reads
        converged_at_first_iteration() after every solve(): whether the solver's own iterations
        converged at their first iteration (the new input changed its solution by less than
        its own tolerance); a solver may then start each coupling iteration from the previous
        iterate. A solver that cannot tell keeps this default, which raises: the coupler stops
        with the message."""
        raise RuntimeError("this solver cannot report whether its own iterations converged at "
                           "their first iteration (solver-coupling convergence)")

    def converged_at_first_iteration(self):
        return False

    def can_substep(self):
        """Substeps (docs/protocol.md, SUBSTEPS): True if the solver can take k steps of its own
        per coupling time step. The SDK then drives each window: the solver sees a run of time
        step delta_t / k whose steps are the substeps, and every coupling iteration is k of its
        steps from the window's start (initialize_step, solve with that substep's input,
        finalize_substep but for the last, which the coupler finalizes once the window has
        converged). For that save_state() keeps the committed state in memory at the window's
        start and restore_state() goes back to it."""
        return False

    def finalize_substep(self):
        """The end of a substep inside a window that has not converged yet: the next substep
        starts from it. By default finalize_step(); a solver that writes its results there
        may leave that to the window's end."""
        self.finalize_step()

    def save_state(self):
        pass

    def restore_state(self):
        pass


def wants_help(argv):
    return any(argument in ("--help", "-h") for argument in argv[1:])


def serve(solver, argv=None):
    """Answer the coupler's requests with the solver's methods until told to stop. Returns the
    exit code: 0 after STOP, 1 on errors or when the coupler has gone, 2 when started outside
    cocopp; --help prints what the program is and returns 0."""
    argv = sys.argv if argv is None else argv
    program = argv[0] if argv else "this solver"
    if wants_help(argv):
        print(f"{program} is a cocopp solver: the cocopp coupler starts it and drives it time "
              "step by step.\nRun it through `cocopp run case.yaml`, with a solver of type "
              "`process` in the case file\nwhose command starts it. The coupler passes the "
              "channel in COCOPP_TRANSPORT and COCOPP_CHANNEL.")
        if type(solver).__doc__:
            print("\n" + type(solver).__doc__.strip())
        return 0
    variables = dict(os.environ)
    channel_file = os.environ.get("COCOPP_CHANNEL_FILE")
    if channel_file:  # a solver the user starts: the coupler wrote its channel there
        try:
            variables = _read_channel_file(channel_file)
        except (OSError, ProtocolError) as error:
            print(f"{program}: cannot connect to the cocopp coupler: {error}", file=sys.stderr)
            return 1
    transport = variables.get("COCOPP_TRANSPORT")
    channel_directory = variables.get("COCOPP_CHANNEL")
    if not transport or not channel_directory:
        print(f"{program}: this program is a cocopp solver; run it through `cocopp run "
              "case.yaml` (COCOPP_TRANSPORT and COCOPP_CHANNEL are not set)", file=sys.stderr)
        return 2
    coupler_pid = os.getppid()
    try:
        if transport == "pipe":
            channel = _PipeChannel(channel_directory, coupler_pid)
        elif transport == "file":
            channel = _FileChannel(channel_directory, coupler_pid)
        elif transport == "tcp":
            channel = _TcpChannel(channel_directory, variables.get("COCOPP_TOKEN", ""))
        else:
            raise ProtocolError(f"unknown transport '{transport}' (pipe, file or tcp)")
    except (OSError, ProtocolError, _ChannelLost) as error:
        print(f"{program}: cannot connect to the cocopp coupler: {error}", file=sys.stderr)
        return 1
    return _Server(solver, channel).run()


# --- the server ---------------------------------------------------------------------------

class _Server:
    def __init__(self, solver, channel):
        self.solver = solver
        self.channel = channel
        self.initialized = False
        self.reporting_convergence = False
        self.substeps = 1          # per coupling time step (SUBSTEPS)
        self.window_delta_t = 0.0  # the coupling time step
        self.window = None         # (step, time) of the window being solved (its end)
        self.window_solves = 0

    def run(self):
        try:
            self.channel.send(struct.pack("<BIq", _HELLO, PROTOCOL_VERSION, os.getpid()))
            while self.handle(self.channel.receive()):
                pass
            return 0
        except _ChannelLost as error:
            print(f"cocopp solver: lost the connection to the coupler: {error}", file=sys.stderr)
            return 1
        except Exception as error:  # the solver's own errors go to the coupler as ERROR
            return self.report_error(str(error) or type(error).__name__)

    def report_error(self, message):
        print(f"cocopp solver: error: {message}", file=sys.stderr)
        try:
            self.channel.send(bytes([_ERROR]) + _string(message))
        except (OSError, _ChannelLost) as error:
            print(f"cocopp solver: could not send the error to the coupler: {error}",
                  file=sys.stderr)
        return 1

    def handle(self, request):
        kind = request[0]
        if kind == _STOP and not self.initialized:
            _expect_size(request, 1)
            self.reply_ok()  # stopped before it started: nothing to finalize
            return False
        if kind not in _REQUEST_NAMES:
            raise ProtocolError(f"unexpected request type {kind}")
        if kind == _SUBSTEPS:
            _expect_size(request, 5)
            (substeps,) = struct.unpack_from("<I", request, 1)
            self.on_substeps(substeps)
            return True
        if kind != _INITIALIZE and not self.initialized:
            raise ProtocolError(f"{_REQUEST_NAMES[kind]} before INITIALIZE")
        if kind == _INITIALIZE:
            _expect_size(request, 13)
            delta_t, timestep_start = struct.unpack_from("<di", request, 1)
            self.on_initialize(RunInfo(delta_t, timestep_start))
        elif kind == _INITIALIZE_STEP:
            _expect_size(request, 13)
            step, time_ = struct.unpack_from("<id", request, 1)
            if self.substeps == 1:
                self.solver.initialize_step(step, time_)
            else:  # the window's substeps start with its first SOLVE
                self.window = (step, time_)
                self.window_solves = 0
                self.solver.save_state()
            self.reply_ok()
        elif kind == _SOLVE:
            if self.substeps == 1:
                self.on_solve(_decode_f64_array(request))
            else:
                self.on_solve_window(_decode_f64_array(request))
        elif kind == _FINALIZE_STEP:
            _expect_size(request, 1)
            self.solver.finalize_step()
            self.reply_ok()
        elif kind == _OUTPUT_STEP:
            _expect_size(request, 1)
            self.solver.output_step()
            self.reply_ok()
        elif kind == _SAVE_RESTART:
            _expect_size(request, 5)
            (step,) = struct.unpack_from("<i", request, 1)
            if self.solver.can_restart():
                self.solver.save_restart(step * self.substeps)
            self.reply_ok()
        elif kind == _REPORT_CONVERGENCE:
            _expect_size(request, 1)
            self.solver.start_reporting_convergence()
            self.reporting_convergence = True
            self.reply_ok()
        else:  # STOP
            _expect_size(request, 1)
            self.solver.finalize()
            self.reply_ok()
            return False
        return True

    def reply_ok(self):
        self.channel.send(bytes([_OK]))

    def on_substeps(self, substeps):
        if self.initialized:
            raise ProtocolError("SUBSTEPS after INITIALIZE")
        if substeps == 0:
            raise ProtocolError("SUBSTEPS of 0: a window has at least one substep")
        if substeps > 1 and not self.solver.can_substep():
            raise RuntimeError(
                f"the case asks this solver for {substeps} substeps per coupling time step, but "
                "it cannot take substeps: it keeps no state in memory to go back to at each "
                "coupling iteration (Solver.can_substep, save_state, restore_state; "
                "docs/protocol.md)")
        self.substeps = substeps
        self.reply_ok()

    def on_initialize(self, run):
        if self.initialized:
            raise ProtocolError("INITIALIZE received twice")
        self.window_delta_t = run.delta_t
        run = RunInfo(run.delta_t / self.substeps, run.timestep_start * self.substeps)
        if run.timestep_start > 0 and not self.solver.can_restart():
            raise RuntimeError(
                f"the coupler restarts the run after time step {run.timestep_start}, but this "
                "solver cannot restart (it saves no restart data): run the case from the start")
        interface = self.solver.initialize(run)
        if not isinstance(interface, Interface):
            raise TypeError("initialize() must return a cocopp_sdk.Interface, not "
                            f"{type(interface).__name__}")
        self.solver.interface = interface
        self.initialized = True
        self.channel.send(_encode_interface(interface))

    def on_solve(self, values):
        interface = self.solver.interface
        if values.size != interface.input_size:
            raise ProtocolError(f"SOLVE carried {values.size} values; the interface takes "
                                f"{interface.input_size}")
        try:
            output = self.solver.solve(values)
        except InputRejected as reason:
            print(f"cocopp solver: input rejected: {reason}", file=sys.stderr)
            self.channel.send(bytes([_REJECTED]) + _string(str(reason)))
            return
        output = _vector(output, interface.output_size, "solve() returned",
                         "as the interface description implies")
        if self.reporting_convergence:
            converged = bool(self.solver.converged_at_first_iteration())
            self.channel.send(bytes([_DATA_CONVERGED]) + _f64_array(output) +
                              bytes([1 if converged else 0]))
        else:
            self.channel.send(bytes([_DATA]) + _f64_array(output))


    def on_solve_window(self, values):
        """SOLVE of a window of substeps: from the window's start, each substep with its
        input; DATA holds the outputs of all, in order."""
        interface, k = self.solver.interface, self.substeps
        if values.size != k * interface.input_size:
            raise ProtocolError(f"SOLVE carried {values.size} values; a window of {k} substeps "
                                f"takes {k * interface.input_size}")
        if self.window_solves > 0:
            self.solver.restore_state()
        self.window_solves += 1
        window_step, window_time = self.window
        outputs, converged = [], True
        for j in range(1, k + 1):
            step = (window_step - 1) * k + j
            time_ = window_time - (k - j) * (self.window_delta_t / k)
            self.solver.initialize_step(step, time_)
            part = values[(j - 1) * interface.input_size:j * interface.input_size]
            try:
                output = self.solver.solve(part)
            except InputRejected as reason:
                self.solver.restore_state()  # the window's start, as a rejection promises
                print(f"cocopp solver: input rejected in substep {j}: {reason}", file=sys.stderr)
                self.channel.send(bytes([_REJECTED]) + _string(str(reason)))
                return
            outputs.append(_vector(output, interface.output_size, "solve() returned",
                                   "as the interface description implies"))
            converged = converged and bool(self.solver.converged_at_first_iteration())
            if j < k:
                self.solver.finalize_substep()
        output = np.concatenate(outputs)
        if self.reporting_convergence:
            self.channel.send(bytes([_DATA_CONVERGED]) + _f64_array(output) +
                              bytes([1 if converged else 0]))
        else:
            self.channel.send(bytes([_DATA]) + _f64_array(output))


# --- encoding -------------------------------------------------------------------------------

def _vector(values, size, what, hint):
    array = np.ascontiguousarray(values, dtype=np.float64).reshape(-1)
    if array.size != size:
        raise ValueError(f"{what} {array.size} values; expected {size} {hint}")
    return array


def _string(text):
    data = text.encode("utf-8", "replace")
    return struct.pack("<I", len(data)) + data


def _names(items):
    return struct.pack("<I", len(items)) + b"".join(_string(item) for item in items)


def _f64_array(values):
    array = np.ascontiguousarray(values, dtype="<f8").reshape(-1)
    return struct.pack("<Q", array.size) + array.tobytes()


def _i64_array(values):
    array = np.ascontiguousarray(values, dtype="<i8").reshape(-1)
    return struct.pack("<Q", array.size) + array.tobytes()


def _encode_interface(interface):
    parts = [struct.pack("<BI", _INTERFACE, len(interface.model_parts))]
    for part in interface.model_parts:
        parts += [_string(part.name), _i64_array(part.ids), _f64_array(part.coordinates),
                  _names(part.inputs), _names(part.outputs)]
    initial = interface.initial_output
    parts.append(_f64_array(np.empty(0) if initial is None else initial))
    return b"".join(parts)


def _expect_size(request, size):
    if len(request) != size:
        raise ProtocolError(f"{_REQUEST_NAMES.get(request[0], request[0])} has {len(request)} "
                            f"bytes; {size} expected")


def _decode_f64_array(request):
    if len(request) < 9:
        raise ProtocolError("SOLVE ends before its value count")
    (count,) = struct.unpack_from("<Q", request, 1)
    if len(request) != 9 + 8 * count:
        raise ProtocolError(f"SOLVE announces {count} values in {len(request)} bytes")
    return np.frombuffer(request, dtype="<f8", count=count, offset=9).astype(np.float64)


# --- transports -----------------------------------------------------------------------------

class _ChannelLost(Exception):
    pass


def _check_coupler(coupler_pid):
    # With files there is no end-of-file; a new parent means the coupler has gone.
    if os.getppid() != coupler_pid:
        raise _ChannelLost("the coupler has exited")


class _StreamChannel:
    """Frames over a byte stream: a length prefix, then the payload. A subclass reads with
    _read_chunk (b"" at the end) and names what the coupler closed in CLOSED."""

    CLOSED = "the coupler closed the channel"

    def _read_chunk(self, size):
        raise NotImplementedError

    def _read_exactly(self, size):
        chunks, remaining = [], size
        while remaining > 0:
            chunk = self._read_chunk(min(remaining, 1 << 20))
            if not chunk:
                raise _ChannelLost(self.CLOSED)
            chunks.append(chunk)
            remaining -= len(chunk)
        return b"".join(chunks)

    def receive(self):
        (length,) = struct.unpack("<I", self._read_exactly(4))
        if not 1 <= length <= MAX_PAYLOAD:
            raise ProtocolError(f"a frame of {length} bytes was announced (corrupt stream?)")
        return self._read_exactly(length)


class _PipeChannel(_StreamChannel):
    """Two FIFOs the coupler created in the channel directory."""

    CLOSED = "the coupler closed the request pipe"

    def __init__(self, directory, coupler_pid):
        # Plain blocking opens, as the protocol allows: the coupler opens its write end of the
        # requests as soon as we open the read end, and already holds the read end of the
        # replies. (A coupler that dies meanwhile takes us with it: PR_SET_PDEATHSIG.)
        self.requests = os.open(os.path.join(directory, "cocopp_to_solver.fifo"), os.O_RDONLY)
        self.replies = os.open(os.path.join(directory, "cocopp_from_solver.fifo"), os.O_WRONLY)

    def _read_chunk(self, size):
        return os.read(self.requests, size)

    def send(self, payload):
        data = memoryview(struct.pack("<I", len(payload)) + payload)
        try:
            while data:
                data = data[os.write(self.replies, data):]
        except BrokenPipeError as error:
            raise _ChannelLost("the coupler closed the reply pipe") from error


def _read_channel_file(path):
    """The VARIABLE=value lines of the file COCOPP_CHANNEL_FILE names (# comments)."""
    variables = {}
    with open(path) as lines:
        for line in lines:
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            name, equals, value = line.partition("=")
            if not equals:
                raise ProtocolError(f"{path}: '{line}' is not VARIABLE=value")
            variables[name] = value
    return variables


class _TcpChannel(_StreamChannel):
    """One TCP connection to the coupler at "host:port": the greeting with the run's token
    first, the coupler's welcome, then frames as over the pipes (docs/protocol.md)."""

    CLOSED = "the coupler closed the connection"

    GREETING = b"COCOPP-TCP-1 "
    WELCOME = b"COCOPP-WELCOME\n"

    def __init__(self, channel, token, timeout=60.0):
        host, _, port = channel.rpartition(":")
        host = host[1:-1] if host.startswith("[") and host.endswith("]") else host
        if not host or not port.isdigit():
            raise ProtocolError(f"COCOPP_CHANNEL '{channel}' is not host:port")
        if len(token) != 64:
            raise ProtocolError("COCOPP_TOKEN is not the run's token (64 hex digits)")
        self.socket = socket.create_connection((host, int(port)), timeout=timeout)
        self.socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.socket.setsockopt(socket.SOL_SOCKET, socket.SO_KEEPALIVE, 1)
        self.socket.sendall(self.GREETING + token.encode() + b"\n")
        try:
            welcome = self._read_exactly(len(self.WELCOME))
        except _ChannelLost:
            raise _ChannelLost(f"the coupler at {channel} refused this solver (is COCOPP_TOKEN "
                               "this run's token?)") from None
        if welcome != self.WELCOME:
            raise ProtocolError(f"the peer at {channel} is not a cocopp coupler")
        self.socket.settimeout(None)  # the coupler's own timeouts bound a step

    def _read_chunk(self, size):
        try:
            return self.socket.recv(size)
        except OSError as error:
            raise _ChannelLost(f"the connection to the coupler was lost: {error}") from error

    def send(self, payload):
        try:
            self.socket.sendall(struct.pack("<I", len(payload)) + payload)
        except OSError as error:
            raise _ChannelLost(f"the connection to the coupler was lost: {error}") from error


class _FileChannel:
    """One file a message: to_solver_00000001.msg, ... (written as .tmp, renamed when ready)."""

    def __init__(self, directory, coupler_pid):
        self.directory = directory
        self.coupler_pid = coupler_pid
        self.incoming = 1
        self.outgoing = 1

    def _name(self, prefix, sequence, extension):
        return os.path.join(self.directory, f"{prefix}_{sequence:08d}{extension}")

    def receive(self):
        path = self._name("to_solver", self.incoming, ".msg")
        pause = 0.001
        while True:
            try:
                descriptor = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
                break
            except FileNotFoundError:
                _check_coupler(self.coupler_pid)
                time.sleep(pause)
                pause = min(2 * pause, 0.02)
        with os.fdopen(descriptor, "rb") as message:
            data = message.read(MAX_PAYLOAD + 5)
        os.unlink(path)
        self.incoming += 1
        if len(data) < 5:
            raise ProtocolError(f"{path} holds {len(data)} bytes, less than a frame")
        (length,) = struct.unpack_from("<I", data)
        if length != len(data) - 4:
            raise ProtocolError(f"{path} announces {length} bytes and holds {len(data) - 4}")
        return data[4:]

    def send(self, payload):
        temporary = self._name("from_solver", self.outgoing, ".tmp")
        try:
            os.unlink(temporary)
        except FileNotFoundError:
            pass
        descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW,
                             0o644)
        with os.fdopen(descriptor, "wb") as message:
            message.write(struct.pack("<I", len(payload)) + payload)
        os.replace(temporary, self._name("from_solver", self.outgoing, ".msg"))
        self.outgoing += 1
