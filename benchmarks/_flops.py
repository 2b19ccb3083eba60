"""Floating-point operations per sample of the compiled kernels, counted by running their
one text on numbers that count (benchmarks/roofline.py reads them).

The formulas (:mod:`offshore_crane.dynamics.backends` binds their code to any arithmetic)
and the compiled linear algebra (:mod:`offshore_crane.dynamics.linear`, called through
``py_func``) run on :class:`Counted` numbers: each ``+ - * /`` and ``sqrt`` between
floating-point values is one operation (a fused multiply-add would be two, as in the
machine's peak); ``sin``, ``cos``, ``atan2`` are counted apart (each is a library call of
tens of operations, reported, not added). Negation, ``abs``, comparisons and copies are
not counted. The count follows the branches the sample takes (the checks' branches that
compute nothing more are free).
"""

from __future__ import annotations

import math
from collections import Counter

import numpy as np

#: What the run counted: {"flop": n, "sin": n, "cos": n, "atan2": n}.
COUNT: Counter = Counter()


def _v(x):
    return x.v if isinstance(x, Counted) else x


class Counted:
    """A float that counts the operations done on it (:data:`COUNT`)."""

    __slots__ = ("v",)

    def __init__(self, v):
        self.v = float(_v(v))

    def _op(self, other, f):
        COUNT["flop"] += 1
        return Counted(f(self.v, _v(other)))

    def __add__(self, o): return self._op(o, lambda a, b: a + b)          # noqa: E704
    def __radd__(self, o): return self._op(o, lambda a, b: b + a)         # noqa: E704
    def __sub__(self, o): return self._op(o, lambda a, b: a - b)          # noqa: E704
    def __rsub__(self, o): return self._op(o, lambda a, b: b - a)         # noqa: E704
    def __mul__(self, o): return self._op(o, lambda a, b: a * b)          # noqa: E704
    def __rmul__(self, o): return self._op(o, lambda a, b: b * a)         # noqa: E704
    def __truediv__(self, o): return self._op(o, lambda a, b: a / b)      # noqa: E704
    def __rtruediv__(self, o): return self._op(o, lambda a, b: b / a)     # noqa: E704
    def __neg__(self): return Counted(-self.v)                            # noqa: E704
    def __pos__(self): return self                                        # noqa: E704
    def __abs__(self): return Counted(abs(self.v))                        # noqa: E704
    def __float__(self): return self.v                                    # noqa: E704
    def __lt__(self, o): return self.v < _v(o)                            # noqa: E704
    def __le__(self, o): return self.v <= _v(o)                           # noqa: E704
    def __gt__(self, o): return self.v > _v(o)                            # noqa: E704
    def __ge__(self, o): return self.v >= _v(o)                           # noqa: E704
    def __eq__(self, o): return self.v == _v(o)                           # noqa: E704
    def __ne__(self, o): return self.v != _v(o)                           # noqa: E704
    __hash__ = None

    def __pow__(self, k):
        if k != 2:
            raise ValueError("only squares are counted")
        return self * self

    def sqrt(self):                         # np.sqrt on an object array calls it
        return _sqrt(self)


def _sqrt(x):
    COUNT["flop"] += 1
    return Counted(math.sqrt(_v(x)))


def _call(name, f):
    def g(*args):
        COUNT[name] += 1
        return Counted(f(*(_v(a) for a in args)))
    return g


MATH = {"sqrt": _sqrt, "sin": _call("sin", math.sin), "cos": _call("cos", math.cos),
        "arctan2": _call("atan2", math.atan2)}


def counted(x):
    """Floats (and float arrays, recursively in tuples) as :class:`Counted`."""
    if isinstance(x, np.ndarray) and x.dtype.kind == "f":
        out = np.empty(x.shape, dtype=object)
        for idx, v in np.ndenumerate(x):
            out[idx] = Counted(v)
        return out
    if isinstance(x, float):
        return Counted(x)
    return x


def objects(*shape, fill=0.0):
    out = np.empty(shape, dtype=object)
    out.fill(Counted(fill))
    return out


def _formulas():
    from offshore_crane.dynamics.backends import bind

    if not _BOUND:
        _BOUND.append(bind(MATH))
    return _BOUND[0]


_BOUND: list = []


def _state(robot, seed=0):
    from offshore_crane.dynamics.constants import robot_arrays
    from offshore_crane.dynamics.formulas import KaneConstants

    C = robot_arrays(robot).kane
    C = KaneConstants(*(counted(x) for x in C))
    rng = np.random.default_rng(seed)
    q = robot.home_pose() + np.r_[rng.uniform(-0.02, 0.02, 6), rng.uniform(-0.5, 0.5, 3)]
    qd, qdd = rng.uniform(-0.3, 0.3, 9), rng.uniform(-1.0, 1.0, 9)
    g = tuple(Counted(x) for x in (0.0, 0.0, -9.81))
    return C, [Counted(x) for x in q], [Counted(x) for x in qd], [Counted(x) for x in qdd], g


def fused_kane(robot) -> Counter:
    """One sample of the fused Kane kernel: the formulas, the 6x6 solve with its
    condition number."""
    from offshore_crane.dynamics import linear
    from offshore_crane.dynamics.formulas import DIAG_ROWS, STORE_WIDTH
    from offshore_crane.robot.kinematics.formulas import LEG_MODEL_CODES

    F = _formulas()
    C, q, qd, qdd, g = _state(robot)
    COUNT.clear()
    rows, A, rhs = [Counted(0.0)] * 3, objects(6, 6), objects(6)
    diag, store = objects(DIAG_ROWS, 6), objects(max(C.n_arm, 1), STORE_WIDTH)
    F.kane_sample(C, q, qd, qdd, g, False, LEG_MODEL_CODES["full"], True, rows, A, rhs,
                  diag, store)
    linear.solve6.py_func(A, rhs, objects(6), objects(6, 13), True)
    return Counter(COUNT)


def _explicit(robot, want_mass: bool, qdd_zero: bool):
    from offshore_crane.dynamics.formulas import DIAG_ROWS, STORE_WIDTH

    F = _formulas()
    C, q, qd, qdd, g = _state(robot)
    if qdd_zero:
        qdd = [Counted(0.0)] * 9
    COUNT.clear()
    B, J, Mm = objects(9), objects(6, 6), objects(9, 9)
    F.explicit_sample(C, q, qd, qdd, g, want_mass, B, J, Mm,
                      objects(max(C.n_arm, 1), STORE_WIDTH), objects(9, 3), objects(9, 3),
                      objects(9, 3), objects(DIAG_ROWS, 6), objects(1, 3))
    return C, B, J, Mm


def explicit_kane(robot) -> Counter:
    """One sample of the explicit Kane kernel: the explicit pass, the leg system, the
    6x6 solve with its condition number."""
    from offshore_crane.dynamics import linear

    C, B, J, _ = _explicit(robot, False, False)
    A, rhs = objects(6, 6), objects(6)
    linear.leg_system.py_func(B, J, Counted(1.0) / C.L, A, rhs)
    linear.solve6.py_func(A, rhs, objects(6), objects(6, 13), True)
    return Counter(COUNT)


def forward_dynamics(robot) -> Counter:
    """One sample of forward dynamics: the explicit pass at q̈ = 0 with the mass matrix,
    ``A X − h``, the Cholesky solve."""
    from offshore_crane.dynamics import linear

    C, B, J, Mm = _explicit(robot, True, True)
    rhs, X = objects(9), counted(np.linspace(-50.0, 50.0, 9))
    linear.actuation_minus_bias.py_func(B, J, X, C.n_arm, rhs)
    linear.cholesky_solve.py_func(Mm, rhs, 6 + C.n_arm, objects(9), objects(9, 9))
    return Counter(COUNT)


def rk4_step(robot) -> Counter:
    """One RK4 step under computed torque on the plant's own model (the rigid plant's
    shared pass, simulation/plants/_rigid_kernels.py): four stages of forward dynamics
    (the explicit pass with the mass matrix, the Cholesky solve) plus the law from that
    pass (q̈_cmd: 5 flops a coordinate; ``M q̈_cmd + h``: 2 n² + ... for n = 9 at most; the
    leg system and its 6x6 solve, counted), and the state update (4 stage combinations of
    18 states: 4 x 18 x 4 flops)."""
    from offshore_crane.dynamics import linear

    fd = forward_dynamics(robot)
    C, B, J, _ = _explicit(robot, False, True)
    COUNT.clear()
    A, rhs = objects(6, 6), objects(6)
    linear.leg_system.py_func(B, J, Counted(1.0) / C.L, A, rhs)
    linear.solve6.py_func(A, rhs, objects(6), objects(6, 13), False)
    n = 6 + C.n_arm
    law = Counter(COUNT)
    law["flop"] += 5 * 9 + 2 * n * n
    total = Counter()
    for _ in range(4):
        total.update(fd)
        total.update(law)
    total["flop"] += 4 * 18 * 4
    return total


def serial_kane(chain) -> Counter:
    """One sample of the serial chain's compiled loop (serial/kernels.py): the arm
    recursion forward and backward on a base at rest, no wrench."""
    from offshore_crane.dynamics.formulas import KaneConstants, STORE_WIDTH
    from offshore_crane.serial import kernels

    F = _formulas()
    C = KaneConstants(*(counted(x) for x in kernels.constants(chain).kane))
    rng = np.random.default_rng(0)
    q, qd, qdd = ([Counted(x) for x in rng.uniform(-1.0, 1.0, chain.n)] for _ in range(3))
    one, nil = Counted(1.0), Counted(0.0)
    R = ((one, nil, nil), (nil, one, nil), (nil, nil, one))
    z = (nil, nil, nil)
    COUNT.clear()
    store = objects(chain.n, STORE_WIDTH)
    F.arm_forward(C, R, z, z, z, q, qd, qdd, 0, (nil, nil, Counted(-9.81)), store, False)
    F.arm_backward(C, store, objects(chain.n))
    return Counter(COUNT)


def _cable_state(robot):
    """The hanging-load robot's constants (the arm continued by the two sway joints and
    the payload) and one state of its 11 coordinates, as counted numbers."""
    from offshore_crane.dynamics.constants import cable_arrays
    from offshore_crane.dynamics.formulas import KaneConstants

    C = KaneConstants(*(counted(x) for x in cable_arrays(robot).kane))
    rng = np.random.default_rng(1)
    q = np.r_[robot.home_pose(), 0.05, -0.03] + np.r_[rng.uniform(-0.02, 0.02, 6),
                                                      rng.uniform(-0.5, 0.5, 3), 0, 0]
    qd, qdd = rng.uniform(-0.3, 0.3, 11), rng.uniform(-1.0, 1.0, 11)
    return C, *([Counted(x) for x in v] for v in (q, qd, qdd))


def swing_step(robot) -> Counter:
    """One RK4 step of the sway along a given motion (dynamics/cable/kernels.py
    ``integrate``): the tip's motion at the two new stage points, four evaluations of the
    pendulum's Kane equations, the stage and combination updates of the 4 sway states
    (3 x 4 x 2 + 4 x 8 flops)."""
    F = _formulas()
    C, q, qd, qdd = _cable_state(robot)
    COUNT.clear()
    for _ in range(2):
        R, w, al, a = F.tip_motion(C, q[:9], qd[:9], qdd[:9])
    g = (Counted(0.0), Counted(0.0), Counted(-9.81))
    L, Ld, Ldd = Counted(1.0), Counted(0.0), Counted(0.0)
    c, z = Counted(0.01), Counted(0.0)         # sway damping; no drag (f = 0)
    for _ in range(4):
        F.hoisted_pendulum(C, R, w, al, a, g, q[9], q[10], qd[9], qd[10], c, c, (z, z, z), L,
                           Ld, Ldd)
    COUNT["flop"] += 3 * 4 * 2 + 4 * 8
    return Counter(COUNT)


def cable_kane(robot) -> Counter:
    """One sample of the hanging load's Kane kernel (the robot's forces with the payload
    swinging: the fused formulas on the arm continued by the sway joints, the 6x6 solve
    with its condition number, the cable's pull)."""
    from offshore_crane.dynamics import linear
    from offshore_crane.dynamics.formulas import DIAG_ROWS, STORE_WIDTH
    from offshore_crane.robot.kinematics.formulas import LEG_MODEL_CODES

    F = _formulas()
    C, q, qd, qdd = _cable_state(robot)
    g = (Counted(0.0), Counted(0.0), Counted(-9.81))
    COUNT.clear()
    rows, A, rhs = objects(C.n_arm), objects(6, 6), objects(6)
    store = objects(C.n_arm, STORE_WIDTH)
    F.kane_sample(C, q, qd, qdd, g, False, LEG_MODEL_CODES["full"], True, rows, A, rhs,
                  objects(DIAG_ROWS, 6), store)
    linear.solve6.py_func(A, rhs, objects(6), objects(6, 13), True)
    F.cable_force(C, store)
    return Counter(COUNT)


def legs_geometry(robot) -> Counter:
    """One sample of the six legs' geometry (``formulas.leg_geometry``: S_i from the
    platform's pose, the leg's length, unit vector and components in the U-joint frame),
    what benchmarks/roofline.py's layout rows run; the attitude comes in precomputed."""
    F = _formulas()
    C, q, *_ = _state(robot)
    R = tuple(tuple(Counted(x) for x in row) for row in np.eye(3))
    COUNT.clear()
    for i in range(6):
        F.leg_geometry(tuple(q[:3]), R, tuple(C.leg_s[i]), tuple(C.leg_P[i]),
                       tuple(C.leg_X[i]), tuple(C.leg_Y[i]), tuple(C.leg_Z[i]))
    return Counter(COUNT)
