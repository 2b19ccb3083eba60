"""Exception tree of offshore-crane.

Every error raised on purpose by the library derives from :class:`OffshoreCraneError`,
so a caller (and the command line) can catch one class. Each exception carries its data
as attributes (the offending value, the sample index, ...) as well as a message that says
what to do about it.
"""

from __future__ import annotations


class OffshoreCraneError(Exception):
    """Root of every error raised on purpose by offshore-crane."""


class InputError(OffshoreCraneError, ValueError):
    """An argument has a wrong shape, a non-finite value or a value out of its domain.

    Attributes:
        name: Name of the offending argument or column.
        index: Index of the first offending time sample, or None.
    """

    def __init__(self, message: str, name: str | None = None, index: int | None = None):
        super().__init__(message)
        self.name = name
        self.index = index


class TrajectoryError(InputError):
    """A trajectory cannot be built or read (unknown name, bad CSV, bad time axis).

    Attributes:
        path: The file concerned, or None.
    """

    def __init__(self, message: str, name: str | None = None, index: int | None = None,
                 path: str | None = None):
        super().__init__(message, name=name, index=index)
        self.path = path


class SceneError(InputError):
    """A scene file (TOML) cannot be read, or has an unknown key or a bad value.

    The message starts with the file and names the key, e.g.
    ``scenes/x.toml: [payload] mass = -1: must be ≥ 0 kg``.

    Attributes:
        path: The scene file as given (or ``"command line"``), or None.
        name: The key as ``section.key`` (``"payload.mass"``), a top-level key
            (``"gravity"``) or a section (``"payload"``), or None for the whole file.
    """

    def __init__(self, message: str, path: str | None = None, name: str | None = None):
        super().__init__(message, name=name)
        self.path = path


class ModelError(OffshoreCraneError, ValueError):
    """The robot description is invalid or has a structure the library cannot handle.

    Attributes:
        element: Name of the URDF link, joint or xacro argument concerned, or None.
    """

    def __init__(self, message: str, element: str | None = None):
        super().__init__(message)
        self.element = element


class DescriptionError(ModelError):
    """A robot description file (TOML) or an override of it is invalid.

    The message is one line that starts with the file (or ``override``) and names the
    field with its dotted name, e.g.
    ``lab.toml: legs.lower.com: z = 0.5 m lies outside the part (0 to 0.42 m)``.

    Attributes:
        path: The description file as given, ``"override"`` for a value set by
            ``load_robot(overrides=...)``, ``--set`` or a scene, or None.
        field: Dotted name of the field (``"legs.lower.com"``), or None for the file.
    """

    def __init__(self, message: str, path: str | None = None, field: str | None = None):
        super().__init__(message, element=field)
        self.path = path
        self.field = field


class WorkspaceError(OffshoreCraneError, ValueError):
    """A pose lies outside the workspace (leg stroke, joint limit, unreachable pose).

    Attributes:
        joint: Name of the joint or leg concerned.
        index: Index of the first offending time sample.
        value: The offending value, in SI units of that joint.
    """

    def __init__(self, message: str, joint: str | None = None, index: int | None = None,
                 value: float | None = None):
        super().__init__(message)
        self.joint = joint
        self.index = index
        self.value = value


class SingularConfigurationError(OffshoreCraneError, ArithmeticError):
    """The linear system of the inverse dynamics is (numerically) singular.

    Attributes:
        index: Index of the first offending time sample.
        time: Time of that sample [s], or None when the caller gave no time axis.
        condition: Condition number (1-norm) measured there.
        kind: Which singularity: "leg-jacobian", "u-joint" or "attitude".
    """

    def __init__(self, message: str, index: int | None = None, time: float | None = None,
                 condition: float | None = None, kind: str | None = None):
        super().__init__(message)
        self.index = index
        self.time = time
        self.condition = condition
        self.kind = kind


class NumericalError(OffshoreCraneError, ArithmeticError):
    """A result is not finite (NaN or inf): the computation overflowed or was undefined.

    Attributes:
        index: Index of the first offending time sample, or None.
        name: The quantity concerned (an actuator such as ``"Fl3"``), or None.
    """

    def __init__(self, message: str, index: int | None = None, name: str | None = None):
        super().__init__(message)
        self.index = index
        self.name = name


class ConstraintResidualError(OffshoreCraneError, ArithmeticError):
    """A closed-loop solve left a loop-closure or equation-of-motion residual above its bound.

    Raised by the constrained-dynamics reference (:mod:`offshore_crane.reference`) when
    the loop-closure Newton iteration does not converge, or when a measured residual of a
    solved sample exceeds its stated bound.

    Attributes:
        index: Index of the first offending time sample.
        kind: ``"position"`` [m], ``"velocity"`` [m/s], ``"acceleration"`` [m/s²],
            ``"dynamics"`` [N, N·m] or ``"proximal"`` (Pinocchio's solver did not reach
            its accuracy).
        residual: The residual measured there, in the units of ``kind``.
        bound: The bound it exceeded, same units.
    """

    def __init__(self, message: str, index: int | None = None, kind: str | None = None,
                 residual: float | None = None, bound: float | None = None):
        super().__init__(message)
        self.index = index
        self.kind = kind
        self.residual = residual
        self.bound = bound


class SimulationError(OffshoreCraneError, RuntimeError):
    """A simulation stopped early: it left the workspace, reached a singular configuration
    or diverged.

    Attributes:
        time: Simulated time of the stop [s].
        cause: What happened, in words.
        result: The run up to that point (every sample computed is kept).
        stop_cause: What happened, as a :class:`offshore_crane.stops.StopCause` (None
            where the stopping loop does not say).
    """

    def __init__(self, message: str, time: float | None = None, cause: str | None = None,
                 result=None, stop_cause=None):
        super().__init__(message)
        self.time = time
        self.cause = cause
        self.result = result
        self.stop_cause = stop_cause


class OutputError(OffshoreCraneError, OSError):
    """An output file cannot be written where asked (checked before computing) or its
    write failed; nothing was left behind.

    Attributes:
        path: The path as given.
        reason: Why, in words.
    """

    def __init__(self, message: str, path: str | None = None, reason: str | None = None):
        super().__init__(message)
        self.path = path
        self.reason = reason

    def __str__(self) -> str:                  # OSError's own formatting would add errno
        return self.args[0]


class BackendMissingError(OffshoreCraneError, ImportError):
    """An optional dependency (pinocchio, matplotlib, xacro, yourdfpy) is not installed.

    Attributes:
        package: The pip package that provides it.
    """

    def __init__(self, message: str, package: str):
        super().__init__(message)
        self.package = package


class SeaStateError(InputError):
    """A sea state, a vessel's RAO table or a crane operation cannot be used.

    Raised by :mod:`offshore_crane.motion.sea` and :mod:`offshore_crane.motion.operations` for values out
    of their domain (``Hs <= 0``, ``gamma < 1``, a heading the RAO table does not cover,
    a waypoint outside a joint's limits) and for malformed RAO files; the message of a file
    error starts with ``file, line N, column C``.

    Attributes:
        name: The argument or CSV column concerned (``"hs"``, ``"amplitude"``), or None.
        index: Index of the offending sample, waypoint or data row, or None.
        path: The RAO file as given, or None.
        line: 1-based line of the file, or None.
        column: The file's column name (``"phase_rad"``), or None.
    """

    def __init__(self, message: str, name: str | None = None, index: int | None = None,
                 path: str | None = None, line: int | None = None, column: str | None = None):
        super().__init__(message, name=name, index=index)
        self.path = path
        self.line = line
        self.column = column


class SeaWorkspaceError(WorkspaceError):
    """A Froude-scaled ship motion leaves the robot's workspace (leg stroke, U-joint).

    Raised by :func:`offshore_crane.motion.sea.platform_trajectory`; the message names the sample,
    the leg and the value at the requested scale, and the smallest scale at which the whole
    record fits, or says that no scale fits because the rotations alone leave the workspace.

    Attributes:
        joint, index, value: As :class:`WorkspaceError`, at the requested scale.
        scale: The requested Froude scale lambda (full-scale length / model length).
        min_scale: The smallest scale found to fit (within the bisection's tolerance), or
            None when no scale fits.
        rotations_only: True when the rotations alone (lambda -> infinity) leave the
            workspace, so that no scale fits.
    """

    def __init__(self, message: str, joint: str | None = None, index: int | None = None,
                 value: float | None = None, scale: float | None = None,
                 min_scale: float | None = None, rotations_only: bool = False):
        super().__init__(message, joint=joint, index=index, value=value)
        self.scale = scale
        self.min_scale = min_scale
        self.rotations_only = rotations_only


def require(module: str, package: str, purpose: str):
    """Import an optional module lazily, or raise :class:`BackendMissingError`.

    Args:
        module: Importable module name, e.g. ``"pinocchio"``.
        package: Pip package that provides it, e.g. ``"pin"``.
        purpose: What it is needed for, used in the message.

    Returns:
        The imported module.
    """
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as exc:  # pragma: no cover - exercised only without the package
        raise BackendMissingError(
            f"{purpose} needs the Python module '{module}', which is not installed: "
            f"run `pip install {package}`.",
            package=package,
        ) from exc


class SlackCableError(OffshoreCraneError, ArithmeticError):
    """The hanging payload's cable went slack: the tension it would need is ≤ 0, so the
    pendulum model (an inextensible cable, taut) no longer holds there.

    Raised by :mod:`offshore_crane.dynamics.cable` at the first such sample (unless asked to warn
    and mark the samples instead).

    Attributes:
        index: The first slack sample.
        time: Its time [s].
        tension: The tension the model gives there [N] (≤ 0).
        result: The run up to (not including) that sample, every sample computed before it
            kept (a :class:`~offshore_crane.dynamics.cable.CableResult`).
    """

    def __init__(self, message: str, index: int | None = None, time: float | None = None,
                 tension: float | None = None, result=None):
        super().__init__(message)
        self.index = index
        self.time = time
        self.tension = tension
        self.result = result


class InsufficientSeedsError(InputError):
    """Too few records (seeds) for a Gumbel fit of their maxima
    (:func:`offshore_crane.studies.sizing.gumbel_fit`).

    Attributes:
        seeds: How many were given.
        minimum: How many a fit needs (:data:`offshore_crane.studies.sizing.MIN_SEEDS`).
    """

    def __init__(self, message: str, seeds: int | None = None, minimum: int | None = None):
        super().__init__(message, name="seeds")
        self.seeds = seeds
        self.minimum = minimum


class GridError(InputError):
    """A sweep's grid (TOML) cannot be used: unreadable, an unknown key, an empty list, a
    value out of its domain (``hs <= 0``, a robot field's own checks), a key that does not
    apply to the scene. The message starts with the grid file and names the key and the
    index of the value, e.g. ``grid.toml: hs[1] = -1: ...``.

    Attributes:
        path: The grid file as given, or None for a grid given as a dict.
        key: The grid key (``"hs"``, ``"payload.mass"``), or None for the whole grid.
        index: Index of the offending value in its list, or None.
    """

    def __init__(self, message: str, path: str | None = None, key: str | None = None,
                 index: int | None = None):
        super().__init__(message, name=key, index=index)
        self.path = path
        self.key = key


class SpaceError(InputError):
    """A design's space file (``offshore-crane design --space``) cannot be used: unreadable,
    empty, a variable that is not a description field or that the scene itself sets,
    bounds reversed or outside what the description validates, an objective or a
    constraint naming no verdict column and no description field. The message starts
    with the space file and names the table and the key.

    Attributes:
        path: The space file as given, or None for a space given as a dict.
        key: The offending key (a variable's dotted name, a quantity), or None.
    """

    def __init__(self, message: str, path: str | None = None, key: str | None = None):
        super().__init__(message, name=key)
        self.path = path
        self.key = key


class NoFeasibleDesignError(OffshoreCraneError):
    """A design search evaluated its budget and no candidate met every constraint. The
    message names the least-violating candidate (its variables, the constraint it
    breaks most and by how much); its evaluations stay in the results directory.

    Attributes:
        candidate: The least-violating candidate
            (:class:`offshore_crane.studies.design.Candidate`), or None.
        evaluated: How many candidates were evaluated.
    """

    def __init__(self, message: str, candidate=None, evaluated: int = 0):
        super().__init__(message)
        self.candidate = candidate
        self.evaluated = evaluated


class ResultsDirectoryError(OutputError):
    """A sweep's results directory cannot be used: it exists but is not a results
    directory of the same scene (no manifest, another scene's manifest, a file), or its
    manifest is damaged. Nothing was written.

    Attributes:
        path: The directory as given. reason: Why, in words.
    """


class SchedulerError(OffshoreCraneError, ConnectionError):
    """A Dask scheduler cannot be reached (or a local cluster cannot be started).

    Attributes:
        address: The scheduler address as given (``tcp://host:port`` or ``local``).
        reason: Why, in words.
    """

    def __init__(self, message: str, address: str | None = None, reason: str | None = None):
        super().__init__(message)
        self.address = address
        self.reason = reason


class ViewerError(OffshoreCraneError, OSError):
    """The browser viewer cannot start: its port is in use or out of range.

    Attributes:
        host: The address it was to listen on.
        port: The port asked for.
    """

    def __init__(self, message: str, host: str | None = None, port: int | None = None):
        super().__init__(message)
        self.host = host
        self.port = port

    def __str__(self) -> str:                  # OSError's own formatting would add errno
        return self.args[0]
