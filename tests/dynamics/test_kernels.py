"""The Kane kernels: one text on several backends agrees, and the prunings are exact.

The backends (NumPy arrays, Python floats, Numba) run the same formula text
(``offshore_crane.dynamics.backends``), so these tests check the *machinery* (binding,
compilation, chunking, threads), not the formulas: the formulas are checked against the
independent RNEA path (``test_kane_vs_rnea.py``). Tolerance 1e-12 relative for
"identical": the backends evaluate the same operations in the same order, but NumPy's
and Numba's ``sin``/``cos``/``sqrt`` may differ in the last bit, and the 6x6 solves differ
(LAPACK against Gauss–Jordan).
"""

import numpy as np
import pytest

import offshore_crane as oc
from conftest import relative_error
from offshore_crane.dynamics import PYTHON_MAX, REGISTRY, solve
from offshore_crane.dynamics.kernels import Options
from offshore_crane.robot.kinematics.formulas import FULL, MASSLESS, THIN_ROD
from offshore_crane.validation import as_gravity
from problems import random_states

G = as_gravity((0.0, 0.0, -9.81))      # read-only, as the public functions hand it on
EXACT = 1e-12
OPTIONS = [Options(conditioning=True, limits=True, warn=1e5, error=1e8),
           Options(leg_model=THIN_ROD), Options(leg_model=MASSLESS, limits=True),
           Options(legs=False), Options(static=True, conditioning=True)]


def _run(robot, backend, q, qd, qdd, opts, threads=1):
    return REGISTRY[("kane", backend)](robot, q, qd, qdd, G, opts, threads)


@pytest.mark.parametrize("leg_model", [FULL, THIN_ROD, MASSLESS])
def test_python_floats_equal_numpy_arrays(robot, leg_model):
    q, qd, qdd = random_states(robot, 30, seed=21)
    opts = Options(leg_model=leg_model, conditioning=True, limits=True, warn=1e5, error=1e8)
    Xv, kv, hv = _run(robot, "numpy", q, qd, qdd, opts)     # N > PYTHON_MAX: arrays
    for k in range(0, 30, 7):
        Xs, ks, hs = _run(robot, "numpy", q[k:k + 1], qd[k:k + 1], qdd[k:k + 1], opts)
        assert relative_error(Xs[0], Xv[k]) < EXACT
        np.testing.assert_allclose(ks[:, 0], kv[:, k], rtol=1e-10)
    assert PYTHON_MAX >= 1


@pytest.mark.parametrize("chunk", [1, 9, 64, 5000])
def test_chunking_does_not_change_results(robot, chunk):
    from offshore_crane.dynamics.constants import robot_arrays
    from offshore_crane.dynamics.kernels import allocate, run_numpy
    from offshore_crane.robot.kinematics.workspace import new_health

    q, qd, qdd = random_states(robot, 300, seed=4)
    ref = _run(robot, "numpy", q, qd, qdd, Options())[0]
    X, kappa = allocate(300, Options())
    run_numpy(robot_arrays(robot), q, qd, qdd, G, Options(), X, kappa, new_health(),
              chunk=chunk)
    assert relative_error(X, ref) < EXACT


@pytest.mark.parametrize("opts", OPTIONS, ids=str)
def test_numba_kernel_equals_numpy_kernel(robot, opts):
    q, qd, qdd = random_states(robot, 500, seed=31)
    if opts.static:
        q[:, :6] = q[0, :6]
        qd[:, :6] = qdd[:, :6] = 0.0
    Xp, kp, hp = _run(robot, "numpy", q, qd, qdd, opts)
    Xn, kn, hn = _run(robot, "numba", q, qd, qdd, opts)
    np.testing.assert_array_equal(np.isnan(Xn), np.isnan(Xp))
    finite = np.isfinite(Xp)
    assert relative_error(Xn[finite], Xp[finite]) < EXACT
    if kp is not None:
        np.testing.assert_allclose(kn, kp, rtol=1e-10)
    np.testing.assert_allclose(hn, hp, rtol=1e-10)   # same samples; κ to round-off


def test_explicit_backends_agree(robot):
    q, qd, qdd = random_states(robot, 200, seed=32)
    opts = Options(conditioning=True, limits=True, warn=1e5, error=1e8)
    Xp, kp, hp = REGISTRY[("kane-explicit", "numpy")](robot, q, qd, qdd, G, opts, 1)
    Xn, kn, hn = REGISTRY[("kane-explicit", "numba")](robot, q, qd, qdd, G, opts, 1)
    assert relative_error(Xn, Xp) < EXACT
    np.testing.assert_allclose(kn, kp, rtol=1e-10)
    np.testing.assert_allclose(hn, hp, rtol=1e-10)   # same samples; κ to round-off


@pytest.mark.parametrize("method", ["kane", "kane-explicit", "rnea"])
def test_threads_are_bit_identical(robot, method):
    q, qd, qdd = random_states(robot, 1001, seed=33)
    one = solve(robot, q, qd, qdd, method=method, backend="numba")
    two = solve(robot, q, qd, qdd, method=method, backend="numba", threads=2)
    np.testing.assert_array_equal(one.X, two.X)
    np.testing.assert_array_equal(one.condition, two.condition)


def test_health_records_merge_like_one_run(robot):
    """A workspace violation and a warning found in the second thread's block are
    reported at the same sample as with one thread."""
    q, qd, qdd = random_states(robot, 400, seed=34)
    q[300, 8] = 0.5                      # arm_slide beyond its 0.2 m limit
    for threads in (1, 2):
        with pytest.raises(oc.WorkspaceError, match="arm_slide = 0.5 m at sample 300"):
            solve(robot, q, qd, qdd, backend="numba", threads=threads)


def test_arm_only_pruning_is_exact(robot, table1):
    _, q, qd, qdd = table1
    full = solve(robot, q, qd, qdd)
    arm = solve(robot, q, qd, qdd, outputs=["T1", "T2", "Fs"])
    assert relative_error(arm.X[:, :3], full.X[:, :3]) < EXACT
    assert np.isnan(arm.X[:, 3:]).all() and arm.condition is None
    assert "leg kinematics and dynamics (no leg force wanted)" in arm.pruned


@pytest.mark.parametrize("backend", ["numpy", "numba"])
def test_static_platform_pruning_is_exact(robot, table1, backend):
    _, q, qd, qdd = table1
    q = q.copy()
    q[:, :6] = q[100, :6]
    qd, qdd = qd.copy(), qdd.copy()
    qd[:, :6] = qdd[:, :6] = 0.0
    pruned = _run(robot, backend, q, qd, qdd, Options(static=True))[0]
    unpruned = _run(robot, backend, q, qd, qdd, Options())[0]
    assert relative_error(pruned, unpruned) < EXACT
    assert any("static platform" in p for p in solve(robot, q, qd, qdd).pruned)


def test_thin_rod_is_exact_without_axial_inertia():
    """Zero leg radii: no axial inertia, so dropping the leg spin changes nothing."""
    robot = oc.load_robot(leg_lower_radius=0.0, leg_upper_radius=0.0)
    q, qd, qdd = random_states(robot, 200, seed=8)
    full = oc.inverse_dynamics(robot, q, qd, qdd)
    thin = oc.inverse_dynamics(robot, q, qd, qdd, leg_model="thin-rod")
    assert relative_error(thin, full) < EXACT
    ref = oc.inverse_dynamics(robot, q, qd, qdd, method="rnea")
    assert relative_error(thin, ref) < 1e-9


def test_massless_model_matches_a_massless_robot():
    robot = oc.load_robot()
    light = oc.load_robot(leg_lower_mass=0.0, leg_upper_mass=0.0)
    q, qd, qdd = random_states(robot, 200, seed=12)
    approx = oc.inverse_dynamics(robot, q, qd, qdd, leg_model="massless")
    ref = oc.inverse_dynamics(light, q, qd, qdd, method="rnea")
    assert relative_error(approx, ref) < 1e-9


def test_approximations_differ_and_are_labelled(robot, table1):
    _, q, qd, qdd = table1
    full = solve(robot, q, qd, qdd)
    thin = solve(robot, q, qd, qdd, leg_model="thin-rod")
    assert full.approximations == ()
    assert thin.approximations and "thin-rod" in thin.approximations[0]
    assert 1e-12 < relative_error(thin.X, full.X) < 1e-3
    with pytest.raises(oc.InputError, match="leg model 'thin-rod' is an approximation"):
        solve(robot, q, qd, qdd, method="rnea", leg_model="thin-rod")


@pytest.mark.parametrize("backend", ["numpy", "numba"])
def test_twist_form_survives_the_attitude_singularity(robot, backend):
    """At pitch q5 = π/2 the explicit form's Jᵀ is singular; the fused solve is not."""
    q, qd, qdd = random_states(robot, 20, seed=2)
    q[:, 4] = np.pi / 2
    q[:, 3] = q[:, 5] = 0.0
    res = solve(robot, q, qd, qdd, limits=False, checks=False, backend=backend)
    assert np.isfinite(res.X).all()


@pytest.mark.filterwarnings("ignore::offshore_crane.robot.kinematics.workspace."
                            "OffshoreCraneWarning")
def test_public_calls_hand_the_kernels_one_signature(robot):
    """Gravity as a tuple, a list, a writable or a read-only array, thresholds as ints or
    floats: the public functions give the compiled kernels one argument type each, so
    each kernel compiles once (a read-only gravity and a writable one, or an int
    threshold, were each a further compile of ~20 s of the fused Kane kernel)."""
    from offshore_crane.dynamics import compiled
    from offshore_crane.robot.kinematics.workspace import Thresholds

    q, qd, qdd = random_states(robot, 4, seed=3)
    kernels = (compiled.kane, compiled.explicit, compiled.forward)
    before = [len(k.signatures) for k in kernels]
    read_only = np.array([0.0, 0.0, -9.81])
    read_only.flags.writeable = False
    for g in ((0.0, 0.0, -9.81), [0, 0, -9.81], np.array([0.0, 0.0, -9.81]), read_only):
        for th in (Thresholds(), Thresholds(10, 10 ** 9)):
            for method in ("kane", "kane-explicit"):
                X = oc.inverse_dynamics(robot, q, qd, qdd, gravity=g, thresholds=th,
                                        method=method, backend="numba", limits=False)
            oc.forward_dynamics(robot, q, qd, X, gravity=g, thresholds=th, limits=False)
            oc.forward_dynamics(robot, q[0], qd[0], X[0], gravity=g)
    added = [len(k.signatures) - b for k, b in zip(kernels, before)]
    assert max(added) <= 1, added


@pytest.mark.parametrize("which", ["robot", "cable", "no arm"])
def test_compiled_views_are_the_constants(robot, which):
    """The compiled kernels rebuild the constants from one flat buffer (``unpack``, its
    views written directly by ``views.c_view``): each view equals the constant the
    description gives (the Python-side views of the same buffer), bit for bit, has its
    shape, is C-contiguous and reads the buffer itself (a view, not a copy)."""
    from offshore_crane.dynamics import compiled
    from offshore_crane.dynamics.constants import FIELDS, cable_arrays, robot_arrays

    if which == "cable":
        arrays = cable_arrays(oc.load_robot(overrides={"payload.mass": 2.0,
                                                       "payload.cable_length": 0.5}))
    elif which == "no arm":
        arrays = robot_arrays(oc.load_robot(with_arm=0))
    else:
        arrays = robot_arrays(robot)
    C, lim_arm, lim_stroke, lim_ujoint = compiled.unpack(arrays.flat, arrays.layout,
                                                         arrays.prismatic)
    views = {**C._asdict(), "lim_arm": lim_arm, "lim_stroke": lim_stroke,
             "lim_ujoint": lim_ujoint}
    expected = {**arrays.kane._asdict(), **{f"lim_{k}": v for k, v in (
        ("arm", arrays.limits.arm), ("stroke", arrays.limits.stroke),
        ("ujoint", arrays.limits.ujoint))}}
    for name in FIELDS:
        got, want = np.asarray(views[name]), np.asarray(expected[name])
        assert got.shape == want.shape, name
        np.testing.assert_array_equal(got, want, err_msg=name)
        if got.ndim:
            assert got.flags.c_contiguous, name
        if got.ndim and got.size:
            assert np.shares_memory(got, arrays.flat), name
    assert C.n_arm == arrays.kane.n_arm


def test_views_without_an_owner_are_only_made_of_a_kernels_arguments():
    """``views.c_view`` (and ``unpack``, the carvers, which call it) and ``views.unowned``
    make arrays that do
    not keep their buffer alive: the buffer must be an argument of the running kernel
    (or an element of one, or unpacked from one), never an array the kernel made. Every
    call site in the package's sources, read with ``ast``."""
    import ast
    from pathlib import Path

    def own(fn):                            # fn's nodes, not those of functions in it
        todo = list(fn.body)
        while todo:
            node = todo.pop()
            yield node
            if not isinstance(node, (ast.FunctionDef, ast.Lambda)):
                todo.extend(ast.iter_child_nodes(node))

    makers = {"c_view", "unpack", "_carve", "carve", "carve_ws", "_work", "_ws", "unowned",
              "carve_accelerations", "carve_law", "carve_tension"}
    root = Path(oc.__file__).parent
    sites = 0
    for path in root.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for fn in (n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)):
            params = {a.arg for a in fn.args.args}
            for node in own(fn):               # names unpacked from an argument: a, b = P
                if (isinstance(node, ast.Assign) and isinstance(node.value, ast.Name)
                        and node.value.id in params and isinstance(node.targets[0], ast.Tuple)):
                    params |= {e.id for e in node.targets[0].elts if isinstance(e, ast.Name)}
            for call in (n for n in own(fn) if isinstance(n, ast.Call)):
                f = call.func               # c_view(...), or c.unpack(...) (not struct's)
                name = f.id if isinstance(f, ast.Name) else (
                    f.attr if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name)
                    and f.value.id in {"c", "compiled", "ep", "views"} else None)
                if name not in makers or not call.args:
                    continue
                buf = call.args[0]
                where = f"{path.relative_to(root)}:{call.lineno}"
                # a tuple written out: each of its elements an argument
                for base in (buf.elts if isinstance(buf, ast.Tuple) else [buf]):
                    base = base.value if isinstance(base, ast.Subscript) else base
                    assert isinstance(base, ast.Name) and base.id in params, where
                sites += 1
    assert sites >= 30                          # the rule was applied to the call sites


def test_unowned_keeps_the_data_and_refuses_what_it_cannot_strip():
    """``views.unowned`` returns its tuple with the same arrays' data (nested tuples and
    numbers kept); a value it cannot strip (a string) is refused when the caller
    compiles."""
    import numba

    from offshore_crane.dynamics.views import unowned

    @numba.njit
    def total(P):
        Q = unowned(P)
        return Q[0].sum() + Q[1] + Q[2][0].sum()

    assert total((np.arange(3.0), 2.5, (np.ones((2, 2)),))) == 3.0 + 2.5 + 4.0

    @numba.njit
    def bad(P):
        return unowned(P)

    with pytest.raises(numba.core.errors.TypingError, match="unowned"):
        bad(("text", np.zeros(1)))


@pytest.mark.parametrize("na", [0, 3, 5])
def test_the_rigid_loops_carved_work_arrays_are_its_workspaces(na):
    """``eq.carve`` lays the loop's work arrays out in a buffer of ``eq.work_size``:
    each view has the shape of the array ``eq.workspaces`` allocates, the views tile the
    buffer without overlap, and the last ends at the buffer's end (no overrun);
    ``eq.carve_ws`` gives the first tuple's views, the same arrays."""
    import numba

    from offshore_crane.simulation import rigid_equations as eq

    @numba.njit
    def views(w, na):               # the views leave compiled code: w stays alive below
        ws, wl = eq.carve(w, na)
        return ws + wl, eq.carve_ws(w, na)

    w = np.zeros(eq.work_size(na))
    carved, first = views(w, na)
    ws, wl = eq.workspaces(na)
    assert [(a.ctypes.data, a.shape) for a in first] == [
        (a.ctypes.data, a.shape) for a in carved[:len(ws)]]
    assert [a.shape for a in carved] == [a.shape for a in ws + wl]
    starts = [(a.ctypes.data - w.ctypes.data) // 8 for a in carved]
    ends = [s + a.size for s, a in zip(starts, carved)]
    assert starts == [0] + ends[:-1]
    assert ends[-1] == w.size
