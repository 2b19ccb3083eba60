"""``identify``'s logs: read as they stream, refused when they record a run identify cannot
model (a hanging or elastic load, a winch, another robot: their columns say so), checked
against the robot's workspace, differentiated, their memory bounded before they are read.

What identify models: the robot of the description, rigid, its payload welded to the
tip, every actuator it has logged. A run's CSV says otherwise in its columns: the sway
and tension of a hanging load (``simulate``/``id --out``: ``phi1_rad, phi2_rad,
tension_N``), the payload's position on an elastic cable, a winch's line; the forces of
an actuator the robot has not (or none of an arm it has: ``nan`` throughout is what
``id`` writes for a platform without the arm; zero throughout, what ``simulate`` writes).
"""

from __future__ import annotations

from typing import NamedTuple

from offshore_crane.errors import InputError

#: The positions' low-pass when the log has no rates [Hz].
DEFAULT_CUTOFF = 5.0
#: Bytes identify holds per sample of a log at its peak: the numbers read, then the
#: positions, their low-passed copy and two derivatives, the forces and the filter's
#: padding of one column (measured with tracemalloc: 450 B a sample on a log of 10⁵
#: samples without rates, the fit's phase 296 B), with room.
BYTES_PER_SAMPLE = 600.0
#: Bytes that do not grow with the log, with room: the libraries identify loads
#: (NumPy, SciPy, Pinocchio, the kernels) and its fixed work, a block of the regressor
#: and the fit's triangles (~27 MB with blocks of 1024 samples) and a chunk of the file's
#: text parsed (~10 MB). Measured: a peak resident set of 0.31 GB on a 20 s log at 1 kHz
#: and 0.37 GB on 200 s (benchmarks/identification_memory.py).
FIXED_BYTES = 3.5e8


class Log(NamedTuple):
    """A log ready for the fit, the filter's ends dropped.

    Attributes:
        path: As given. t: ``(N,)`` [s]. q, qd, qdd: ``(N, 9)`` [m, rad], rates,
        accelerations. X: ``(N, 9)`` [N·m, N] (NaN for actuators the robot has not).
    """

    path: str
    t: object
    q: object
    qd: object
    qdd: object
    X: object

    @property
    def nbytes(self) -> int:
        return sum(a.nbytes for a in (self.t, self.q, self.qd, self.qdd, self.X))


def load_columns() -> dict:
    """``{column: what it records}``: the columns of a run whose payload hangs on a cable
    (what ``simulate --out`` and ``id --out`` write), which identify cannot model."""
    from offshore_crane.cli.simulate import ELASTIC_COLUMNS as SIMULATED
    from offshore_crane.outputs.report import CABLE_COLUMNS, ELASTIC_COLUMNS, WINCH_COLUMNS

    out = {}
    for columns, what in ((CABLE_COLUMNS, "a payload swinging on a cable"),
                          (ELASTIC_COLUMNS, "a payload on an elastic cable"),
                          (WINCH_COLUMNS, "a winch hoisting the payload"),
                          (SIMULATED, "a payload on an elastic cable")):
        for c in columns.split(","):
            out.setdefault(c, what)
    return out


def _header_check(path: str, what: str):
    """The refusals a log's header decides: a hanging load's columns, forces alone."""
    from offshore_crane.conventions import Q_COLUMNS

    loads = load_columns()

    def check(header: list) -> None:
        found = [c for c in header if c in loads]
        if found:
            shown = ", ".join(found[:3]) + (f" and {len(found) - 3} more" if len(found) > 3
                                            else "")
            raise InputError(f"{what} {path}: columns {shown} record {loads[found[0]]}: "
                             "identify models the payload welded; log a run with "
                             "payload.cable_length = 0", name=what)
        if "t_s" in header and Q_COLUMNS[0] not in header and "T1_Nm" in header:
            raise InputError(f"{what} {path}: forces without positions (what offshore-crane "
                             "id writes): give a run's log with t_s, q1..q9 and the forces "
                             "(simulate --out writes one)", name=what)
    return check


def read_log(path: str, what: str, robot, cutoff: float | None, held: float = 0.0) -> Log:
    """A log read, checked and differentiated for the fit of ``robot``.

    Args:
        path: The run's CSV. what: its option (``"--log"``, ``"--validate"``).
        cutoff: Low-pass [Hz] of the positions (None: the log's own rates if it has
            them, else :data:`DEFAULT_CUTOFF`).
        held: Bytes already held for other logs (the memory check counts them).

    Raises:
        InputError: a hanging load's columns, forces alone or none, a run of another robot
            (the arm's forces where the robot has none or none where it has one, positions
            outside its workspace), positions the filter takes out of the workspace, a
            log too short for the filter, or more memory than the limit; the reader's
            errors (:func:`offshore_crane.outputs.visual.motion.read_run`).
    """
    import numpy as np

    from offshore_crane.outputs.visual.motion import read_run
    from offshore_crane.studies import identification as ident

    m = read_run(path, what, header_check=_header_check(path, what),
                 memory=lambda rows: held + FIXED_BYTES + BYTES_PER_SAMPLE * rows)
    if m.X is None:
        raise InputError(f"{what} {path}: the log has no actuator forces (columns "
                         "T1_Nm..Fl6_N): identification needs them", name=what)
    _same_robot(m, robot, path, what)
    _inside(robot, m.q, m.t, path, what, "")
    X = np.nan_to_num(m.X, copy=False, nan=0.0)      # an actuator the robot has not: unread
    if m.qd is not None and m.qdd is not None and cutoff is None:
        return Log(path, m.t, m.q, m.qd, m.qdd, X)
    cutoff = cutoff or DEFAULT_CUTOFF
    t, q = m.t, m.q
    del m                                            # the positions go once filtered
    try:
        keep, q, qd, qdd = ident.log_derivatives(t, q, cutoff)
    except InputError as exc:
        raise InputError(f"{what} {path}: {exc}", name=what) from None
    _inside(robot, q[keep], t[keep], path, what, f" low-passed at {cutoff:g} Hz")
    return Log(path, t[keep], q[keep], qd[keep], qdd[keep], X[keep])


def _same_robot(m, robot, path: str, what: str) -> None:
    """Refuse the log of a robot with or without the crane arm when ``robot`` differs."""
    import numpy as np

    from offshore_crane.outputs.visual.motion import FORCE_COLUMNS

    arm, legs = m.X[:, :3], m.X[:, 3:]
    names = ", ".join(FORCE_COLUMNS[:3])
    absent = np.isnan(m.X).all(axis=0)
    has_arm = robot.hybrid.has_arm
    if has_arm and (absent[:3].all() or (not np.any(arm) and np.any(legs))):
        how = "nan" if absent[:3].all() else "0"
        raise InputError(f"{what} {path}: columns {names} are {how} on every row: a run of "
                         "a platform without the crane arm; give that robot's description "
                         "with --robot", name=what)
    missing = absent & np.r_[[has_arm] * 3, [True] * 6]
    if missing.any():
        shown = ", ".join(c for c, a in zip(FORCE_COLUMNS, missing) if a)
        raise InputError(f"{what} {path}: column(s) {shown} are nan on every row: "
                         "identify needs every actuator's force", name=what)
    if has_arm:
        return
    moved = np.abs(m.q[:, 6:]).max() > 0.0
    if moved or np.nan_to_num(arm).any():
        which = "q7..q9 move" if moved else f"columns {names} hold forces"
        raise InputError(f"{what} {path}: {which}, but the robot ({robot.spec.path}) has no "
                         "crane arm: a run of another robot; give its description with "
                         "--robot", name=what)


def _inside(robot, q, t, path: str, what: str, how: str) -> None:
    """Refuse positions outside the robot's workspace (the regressor needs its loops
    closed): another robot's log, or the filter's."""
    from offshore_crane.errors import WorkspaceError
    from offshore_crane.robot.kinematics import check_workspace

    try:
        check_workspace(robot, q, t)
    except WorkspaceError as exc:
        core = str(exc).rsplit("; ", 1)[0]
        fix = ("a run of another robot? give its description with --robot" if not how else
               "give a lower --cutoff (the logged positions are inside)")
        raise InputError(f"{what} {path}: the positions{how} leave the robot's workspace: "
                         f"{core}: {fix}", name=what) from None
