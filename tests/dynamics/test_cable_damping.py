"""Damping where the sea has it (issue 35, item 3): the sway damping and the air's drag
on the hanging payload, rigid and elastic cable.

References that share nothing with the code under test: the damped rigid swing (the
Kane path, itself checked against Pinocchio's model of the URDF here, which reads the
damping from the URDF's ``<dynamics damping>`` and the drag from its ``<drag>``), the
payload's energy and the power of its dampers written here from the sway angles' own
definition (``atan2``/``asin`` of the cable's direction, not the code's partials), and
the damped oscillator (its period and logarithmic decrement).
"""

import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane.dynamics import backends, cable
from offshore_crane.dynamics.constants import cable_arrays
from offshore_crane.errors import InputError, ModelError
from offshore_crane.motion.trajectories import table1, time_grid
from problems import assert_cable_paths_agree, held_at_home

G = 9.81
MASS, LENGTH = 2.0, 1.0
ZETA = 0.05                                              # 5 % of critical
DAMPING = 2 * ZETA * MASS * LENGTH ** 2 * np.sqrt(G / LENGTH)   # [N·m·s/rad]
DRAG_AREA = 0.5                                          # C_d·A [m²]: k = 0.31 kg/m


def _robot(damping=DAMPING, drag=0.0, **more):
    return oc.load_robot(overrides={"payload.mass": MASS, "payload.cable_length": LENGTH,
                                    "payload.sway_damping": damping,
                                    "payload.drag_area": drag, **more})


@pytest.fixture(scope="module")
def damped():
    return _robot()


@pytest.fixture(scope="module")
def dragged():
    return _robot(drag=DRAG_AREA)


def _tip_axes(robot, q, qd, qdd):
    """``(Rt (N, 3, 3), ω (N, 3))``: the tip frame's attitude and angular velocity (the
    robot's kinematics)."""
    B, C = backends.NUMPY, cable_arrays(robot).kane
    Rt, w = B.tip_motion(C, q.T, qd.T, qdd.T)[:2]
    Rt = np.moveaxis(np.array([[np.asarray(x) * np.ones(len(q)) for x in row]
                               for row in Rt]), -1, 0)
    return Rt, np.stack([np.asarray(x) * np.ones(len(q)) for x in w], axis=-1)


def _angles(r, w):
    """The sway angles and their rates from the cable's direction ``r`` ``(N, 3)`` and
    its rate ``w`` (tip axes): ``φ1 = atan2(u_y, −u_z)``, ``φ2 = −asin(u_x)``
    (``e = Rx(φ1) Ry(φ2) (0, 0, −1)``), differentiated here."""
    d = np.linalg.norm(r, axis=1)[:, None]
    u = r / d
    ud = (w - np.sum(w * u, axis=1)[:, None] * u) / d
    phi = np.column_stack([np.arctan2(u[:, 1], -u[:, 2]), -np.arcsin(u[:, 0])])
    rate = np.column_stack([(-ud[:, 1] * u[:, 2] + u[:, 1] * ud[:, 2])
                            / (u[:, 1] ** 2 + u[:, 2] ** 2),
                            -ud[:, 0] / np.cos(phi[:, 1])])
    return phi, rate


def _simpson(t, y):
    """``∫ y dt`` from t[0] to every even sample (Simpson's rule, uniform t)."""
    h = t[1] - t[0]
    pieces = h / 3 * (y[0:-2:2] + 4 * y[1:-1:2] + y[2::2])
    return np.concatenate([[0.0], np.cumsum(pieces)])


# --------------------------------------------------------------------------- EA → ∞
def _limit(robot, eas):
    """The elastic swing along Table 1 (5 s at 1 kHz) started as the rigid one (its
    direction, rate and initial tension's stretch) from a 3-D sway (0.3, 0.2) rad: the
    largest distance from the rigid swing's payload [m] and of X [relative] per EA."""
    t = time_grid(5.0, 1000.0)
    q, qd, qdd = table1(t)
    rigid = cable.inverse_dynamics(robot, q, qd, qdd, t=t, reference=table1,
                                   initial=(0.3, 0.2))
    Rt, w = _tip_axes(robot, q, qd, qdd)
    B = backends.NUMPY
    e, e1, e2 = (np.stack(x, axis=-1) for x in B.sway_direction(rigid.sway[:, 0],
                                                                  rigid.sway[:, 1]))
    rho = np.einsum("nij,nj->ni", Rt, e) * LENGTH
    rel = np.einsum("nij,nj->ni", Rt, e1 * rigid.sway_rate[:, :1]
                    + e2 * rigid.sway_rate[:, 1:]) * LENGTH
    pos, X = [], []
    for ea in eas:
        el = cable.elastic_inverse_dynamics(
            robot, q, qd, qdd, t=t, reference=table1, ea=ea,
            initial=rho[0] * (1 + rigid.tension[0] / ea),
            initial_velocity=np.cross(w[0], rho[0]) + rel[0])
        pos.append(np.abs(el.position - rho).max())
        X.append(np.abs(el.X - rigid.X).max() / np.abs(rigid.X).max())
    return np.array(pos), np.array(X)


@pytest.mark.parametrize("drag", [0.0, DRAG_AREA], ids=["sway damping", "and drag"])
def test_the_elastic_swing_tends_to_the_damped_rigid_one(drag):
    """With the sway damping (ζ = 5 %) and with the drag too, the elastic payload tends to
    the damped rigid swing as 1/EA (the rigid cable's EA → ∞ limit): from EA = 1e5 to
    1e8 N the payload's distance from it falls 10× a decade (measured 10.00, 10.00, 10.00
    with and without drag; bound 9.5 to 10.5) to 3.1e-7 m (2.4e-7 with drag) and X to
    1.8e-7 (1.5e-7) of its peak. With the damping applied isotropically across the cable
    (``c / L²`` of the transverse velocity, without the per-angle part along ê1:
    ``SWAY_DAMPING_CONDITION`` = 1) the distance stalls at 2.3e-2 m and X at 4.6e-3 of
    its peak whatever EA (measured from 1e4 to 1e8 N): the test tells the two apart."""
    pos, X = _limit(_robot(drag=drag), (1e5, 1e6, 1e7, 1e8))
    ratio = pos[:-1] / pos[1:]
    assert (ratio > 9.5).all() and (ratio < 10.5).all(), ratio
    assert pos[-1] <= 5e-7 and X[-1] <= 5e-7


# --------------------------------------------------------------------------- Pinocchio
@pytest.mark.parametrize("winch", [False, True], ids=["fixed", "winch"])
def test_kane_equals_pinocchio_with_damping_and_drag(dragged, winch):
    """Table 1 (3 s at 100 Hz) from a sway of (0.3, 0.2) rad, ζ = 5 % and C_d·A = 0.5 m²,
    on a fixed cable and with a winch hauling 1.0 → 0.6 → 0.8 m: the swing, X, the pull
    and the tension of Kane's path equal Pinocchio's (drag as ``Jᵀ f`` of the payload's
    frame) to 1e-12 (measured 1.4e-16 rad, 2.5e-15 of peak X). The drag matters: without
    it the sway differs by 0.23 rad and X by 2 %. Before this test the winch's pull took
    no moment (it acted at the tip): 6.2e-3 of peak X from Pinocchio with the sway
    damping."""
    t = time_grid(3.0, 100.0)
    q, qd, qdd = table1(t)
    hoist = cable.hoist_profile([(0.0, 1.0), (1.5, 0.6), (3.0, 0.8)]) if winch else None
    run = dict(t=t, reference=table1, initial=(0.3, 0.2), hoist=hoist)
    k = cable.inverse_dynamics(dragged, q, qd, qdd, **run)
    p = cable.inverse_dynamics(dragged, q, qd, qdd, method="pinocchio", **run)
    assert_cable_paths_agree(k, p, sway=1e-12, rel=1e-12)
    assert np.abs(k.residual).max() <= 1e-12 * MASS * G * LENGTH
    bare = cable.inverse_dynamics(_robot(), q, qd, qdd, **run)
    assert np.abs(bare.sway - k.sway).max() > 0.05


def test_sway_accelerations_take_the_drag(dragged):
    """The right-hand side on NumPy (``sway_accelerations``) equals Pinocchio's at 100
    random states with the drag to 1e-12 of the largest (measured ~1e-15)."""
    from offshore_crane.reference.cable import _Pendulum

    rng = np.random.default_rng(5)
    n = 100
    q, qd, qdd = table1(rng.uniform(0, 10 * np.pi, n))
    sway, rate = rng.uniform(-1, 1, (n, 2)), rng.uniform(-2, 2, (n, 2))
    ours = cable.sway_accelerations(dragged, q, qd, qdd, sway, rate)
    P = _Pendulum(dragged, oc.GRAVITY)
    out, ref = np.empty(4), np.empty_like(ours)
    for k in range(n):
        P.rhs(q[k], qd[k], qdd[k], np.concatenate([sway[k], rate[k]]), out)
        ref[k] = out[2:]
    assert np.abs(ours - ref).max() <= 1e-12 * np.abs(ref).max()


# --------------------------------------------------------------------------- energy
def test_rigid_energy_falls_by_the_dampers_work(dragged):
    """Crane frozen at home, a 3-D swing from (0.5, 0.4) rad for 4 s at 1 kHz: the
    payload's energy falls by the work of the sway damping ``c (φ̇1² + φ̇2²)`` and of the
    drag ``k |v|³`` (Simpson's rule on the 1 ms samples), to 1e-9 of that work (measured
    4.3e-12: RK4 at 1 ms and the quadrature, both O(h⁴)); they take 85 % of it."""
    t, q, qd, qdd = held_at_home(dragged, 4.0, 1000.0)
    res = cable.inverse_dynamics(dragged, q, qd, qdd, t=t, initial=(0.5, 0.4))
    (p1, p2), (r1, r2) = res.sway.T, res.sway_rate.T
    speed2 = LENGTH ** 2 * (np.cos(p2) ** 2 * r1 ** 2 + r2 ** 2)
    energy = 0.5 * MASS * speed2 + MASS * G * LENGTH * (1 - np.cos(p1) * np.cos(p2))
    k = 0.5 * 1.225 * DRAG_AREA
    power = DAMPING * (r1 ** 2 + r2 ** 2) + k * speed2 ** 1.5
    work = _simpson(t, power)
    lost = energy[0] - energy[::2]
    assert lost[-1] > 0.5 * energy[0]                    # the dampers take most of it
    assert np.abs(lost - work).max() <= 1e-9 * work[-1]


def test_elastic_energy_falls_by_the_dampers_work():
    """Crane frozen at home, the payload on EA = 2e4 N with axial damping 5 N·s/m, sway
    damping (ζ = 5 %) and drag, swinging in 3-D from a sideways offset and speed, taut
    throughout (4 s at 1 kHz): its energy (kinetic, potential and the cable's ½ k s²)
    falls by the work of the axial damper ``c ṡ²``, of the sway damping
    ``c (φ̇1² + φ̇2²)`` with φ̇ from the cable's direction, and of the drag ``k |v|³``, to
    1e-7 of that work (measured 4.2e-10: RK4 at 50 steps an axial period; leaving the
    sway damping's term out misses 67 % of it); the sway force does the rigid cable's
    work exactly: ``F_s · ρ̇ = −c (φ̇1² + φ̇2²)`` to 1e-12 (measured 4.2e-15)."""
    robot = _robot(drag=DRAG_AREA)
    ea, c_ax = 2e4, 5.0
    t, q, qd, qdd = held_at_home(robot, 4.0, 1000.0)
    u = np.array([0.4, 0.3, -0.85]) / np.linalg.norm([0.4, 0.3, -0.85])
    v0 = np.array([0.0, 0.8, 0.0]) - 0.8 * u[1] * u          # across the cable
    taut = MASS * (-G * u[2] + v0 @ v0 / LENGTH)             # its tension there [N]
    res = cable.elastic_inverse_dynamics(robot, q, qd, qdd, t=t, ea=ea, damping=c_ax,
                                         initial=u * LENGTH * (1 + taut / ea),
                                         initial_velocity=v0)
    assert (res.tension > 0).all()
    rho, v = res.position, res.velocity
    Rt = _tip_axes(robot, q[:1], qd[:1], qdd[:1])[0][0]
    phi, rate = _angles(rho @ Rt, v @ Rt)
    s = res.stretch
    sd = np.sum(v * rho, axis=1) / np.linalg.norm(rho, axis=1)
    energy = (0.5 * MASS * np.sum(v ** 2, axis=1) + MASS * G * rho[:, 2]
              + 0.5 * ea / LENGTH * s ** 2)
    sway = DAMPING * np.sum(rate ** 2, axis=1)
    assert np.abs(np.sum(res.sway_force * v, axis=1) + sway).max() <= 1e-12 * sway.max()
    k = 0.5 * 1.225 * DRAG_AREA
    power = c_ax * sd ** 2 + sway + k * np.linalg.norm(v, axis=1) ** 3
    assert np.allclose(res.drag, -k * np.linalg.norm(v, axis=1)[:, None] * v, rtol=1e-14,
                       atol=0)
    work = _simpson(t, power)
    lost = energy[0] - energy[::2]
    assert np.abs(lost - work).max() <= 1e-7 * work[-1]


def test_the_sway_damping_acts_while_the_cable_pulls(damped):
    """Thrown up into a slack flight (EA 5e3 N, 1.5 s at 1 kHz: 1244 slack samples) the
    payload gets no sway damping, a slack cable carrying no moment; taut, it does (up to
    0.83 N here)."""
    t, q, qd, qdd = held_at_home(damped, 1.5, 1000.0)
    res = cable.elastic_inverse_dynamics(damped, q, qd, qdd, t=t, ea=5e3,
                                         initial=(0.3, 0.0, -0.8),
                                         initial_velocity=(0.0, 1.5, 0.5))
    slack = res.slack
    assert slack.any() and (~slack).any()
    assert (res.sway_force[slack] == 0).all()
    assert np.abs(res.sway_force[~slack]).max() > 0.01


# --------------------------------------------------------------------------- modes
def _peaks(t, x):
    """Times and values of the maxima of ``x`` (parabola through each sample maximum and
    its neighbours)."""
    k = np.where((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:]))[0] + 1
    a, b, c = x[k - 1], x[k], x[k + 1]
    off = 0.5 * (a - c) / (a - 2 * b + c)
    return t[k] + off * (t[1] - t[0]), b - 0.25 * (a - c) * off


def test_modes_meet_a_free_decay():
    """On EA = 2e4 N with axial damping 20 N·s/m (ζ = 5 % axial) and the sway damping
    (ζ = 5 %), crane frozen: a small sideways swing (1 % of the length, 7 s at 1 kHz) and
    a small stretch (0.1 mm, 1 s) decay with the period ``2π / (ω √(1 − ζ²))`` and the
    logarithmic decrement ``2π ζ / √(1 − ζ²)`` of :func:`cable.modes`: the period to 1e-4
    relative (measured 2.6e-6 sway, 6.0e-6 axial: the parabola through sampled peaks)
    and the decrement to 1e-3 (measured 8.7e-6, 4.0e-5); the rigid cable's pendulum
    likewise (2.5e-6, 4.6e-6)."""
    robot = _robot()
    ea, c_ax = 2e4, 20.0
    sway_x, sway_y, axial = cable.modes(robot, ea=ea, damping=c_ax)
    assert (sway_x.name, sway_y.name, axial.name) == ("sway phi1", "sway phi2", "axial")
    assert sway_x.zeta == sway_y.zeta and abs(axial.zeta - ZETA) < 1e-15
    ell = LENGTH * (1 + MASS * G / ea)
    t, q, qd, qdd = held_at_home(robot, 7.0, 1000.0)
    checks = []
    res = cable.elastic_inverse_dynamics(robot, q, qd, qdd, t=t, ea=ea, damping=c_ax,
                                         initial=(0.0, 0.01 * ell, -ell))
    checks.append((sway_x, *_peaks(t, res.position[:, 1])))
    n = 1000
    res = cable.elastic_inverse_dynamics(robot, q[:n], qd[:n], qdd[:n], t=t[:n], ea=ea,
                                         damping=c_ax, initial=(0.0, 0.0, -ell - 1e-4))
    checks.append((axial, *_peaks(t[:n], -(res.position[:, 2] + ell))))
    rigid = cable.modes(robot)
    res = cable.inverse_dynamics(robot, q, qd, qdd, t=t, initial=(0.0, 0.01))
    checks.append((rigid[1], *_peaks(t, res.sway[:, 1])))
    for mode, tp, xp in checks:
        assert len(tp) >= 3
        period = 2 * np.pi / mode.damped_omega
        assert np.abs(np.diff(tp) / period - 1).max() <= 1e-4, mode
        assert np.abs(np.log(xp[:-1] / xp[1:]) / mode.log_decrement - 1).max() <= 1e-3, mode
    assert rigid[0].omega == pytest.approx(np.sqrt(G / LENGTH), rel=1e-15)
    assert rigid[0].zeta == pytest.approx(ZETA, rel=1e-12)
    assert rigid[0].decay_time == pytest.approx(1 / (ZETA * np.sqrt(G / LENGTH)))


def test_the_drags_equivalent_damping_meets_a_free_decay(dragged):
    """Drag alone (C_d·A = 0.5 m², no sway damping) on the rigid cable, from 0.1 rad: it
    adds nothing to the linearised modes, and at the swing's amplitude X (the geometric
    mean of two successive peaks) its equivalent linear damping ``ζ = 4 k X / (3 π m)``
    gives the measured decrement to 1 % (measured 0.2 %: the decay within a cycle)."""
    robot = _robot(damping=0.0, drag=DRAG_AREA)
    assert all(m.zeta == 0.0 for m in cable.modes(robot))
    t, q, qd, qdd = held_at_home(robot, 6.0, 1000.0)
    res = cable.inverse_dynamics(robot, q, qd, qdd, t=t, initial=(0.0, 0.1))
    tp, xp = _peaks(t, res.sway[:, 1])
    for a, b in zip(xp[:-1], xp[1:]):
        mode = cable.modes(robot, amplitude=LENGTH * np.sin(np.sqrt(a * b)))[1]
        assert np.log(a / b) == pytest.approx(mode.log_decrement, rel=1e-2)


@pytest.mark.parametrize("kwargs, match", [
    (dict(ea=-1.0), r"ea = -1\.0 N: give a finite number > 0"),
    (dict(length=0.0), r"length = 0\.0 m: give a finite number > 0"),
    (dict(damping=2.0), r"damping = 2 N·s/m is the elastic cable's axial damping: give ea"),
    (dict(ea=1e4, damping=-1.0), r"damping = -1\.0 N·s/m: give a finite number >= 0"),
    (dict(amplitude=float("nan")), r"amplitude = nan m"),
    (dict(gravity=(0.0, 0.0, 0.0)), "gravity is zero"),
])
def test_modes_refuse_bad_arguments(damped, kwargs, match):
    with pytest.raises(InputError, match=match):
        cable.modes(damped, **kwargs)


def test_modes_need_a_cable():
    with pytest.raises(ModelError, match="payload is welded to arm_tip"):
        cable.modes(oc.load_robot())


# --------------------------------------------------------------------------- description
def test_drag_fields_flow_through_every_way_in(tmp_path, capsys):
    """``payload.drag_area`` and ``payload.air_density`` reach the URDF's ``<drag>`` and
    ``robot.hybrid`` from ``--set``, a scene's ``[payload]`` and a sweep grid's dotted
    names; a description without drag writes no ``<drag>`` and keeps its digest."""
    from offshore_crane import scenes
    from offshore_crane.cli import main
    from offshore_crane.robot.description import resolve
    from offshore_crane.studies.sweep.grid import case_scene, check_grid

    hang = ["--set", "payload.mass=2", "--set", "payload.cable_length=1"]
    assert main(["describe", *hang, "--set", "payload.drag_area=0.3",
                 "--set", "payload.air_density=1.2"]) == 0
    text = capsys.readouterr().out
    assert "drag_area: 0.3" in text and "air_density: 1.2" in text
    robot = _robot(drag=0.3, **{"payload.air_density": 1.2})
    assert '<drag air_density="1.2" area="0.3"/>' in robot.urdf
    assert robot.hybrid.drag == pytest.approx(0.5 * 1.2 * 0.3, rel=1e-15)
    assert "<drag" not in _robot().urdf and _robot().hybrid.drag == 0.0
    plain = {"payload.mass": 2.0, "payload.cable_length": 1.0}
    assert resolve(None, plain).digest() == resolve(
        None, {**plain, "payload.air_density": 1.0}).digest()      # no drag: unchanged
    scene = tmp_path / "dragged.toml"
    scene.write_text("[payload]\nmass = 2.0\ncable_length = 1.0\ndrag_area = 0.2\n"
                     "air_density = 1.0\n")
    hybrid = scenes.load_robot(scenes.load_scene(scene)).hybrid
    assert (hybrid.drag_area, hybrid.air_density) == (0.2, 1.0)
    base = scenes.load_scene(scene)
    grid = check_grid(base, {"payload.drag_area": [0.0, 0.4]})
    drags = [scenes.load_robot(case_scene(base, case)).hybrid.drag_area
             for case in grid.cases()]
    assert drags == [0.0, 0.4]


@pytest.mark.parametrize("over, match", [
    ({"payload.drag_area": -0.1}, r"payload\.drag_area: -0\.1 m² must not be negative"),
    ({"payload.drag_area": 0.1, "payload.cable_length": 0.0, "payload.sway_damping": 0.0},
     r"payload\.drag_area: 0\.1 m² drags a payload swinging on a cable, but "
     r"payload\.cable_length = 0"),
    ({"payload.air_density": 0.0}, r"payload\.air_density: 0 kg/m³ must be > 0"),
])
def test_bad_drag_fields_are_refused(over, match):
    with pytest.raises(oc.errors.DescriptionError, match=match):
        _robot(**over)


def test_a_urdf_drag_without_cable_or_with_bad_numbers_is_refused():
    from offshore_crane.robot.hybrid import hybrid_from_urdf
    from offshore_crane.robot.urdf import parse_urdf

    text = oc.load_robot().urdf.replace('<link name="payload">',
                                        '<link name="payload"><drag area="0.1" '
                                        'air_density="1.2"/>')
    with pytest.raises(ModelError, match="gives the link 'payload' a <drag>, but the "
                                         "payload does not hang on a cable"):
        hybrid_from_urdf(parse_urdf(text))
    with pytest.raises(ModelError, match=r"link 'payload' <drag>: area = -1 m² must be"):
        parse_urdf(text.replace('area="0.1"', 'area="-1"'))


def test_the_tip_frame_is_the_tip_state_and_the_tip_motions_frame_bit_for_bit():
    """``tip_frame`` (one call where the elastic cable wants the tip's place and frame)
    gives :func:`tip_state`'s position and velocity and :func:`tip_motion`'s attitude
    and angular velocity, bit for bit (the same operations), compiled and on Python
    floats, for a revolute and a prismatic arm joint."""
    from offshore_crane.dynamics import compiled as c

    robot = _robot()
    C = cable_arrays(robot).kane
    rng = np.random.default_rng(43)
    n = 6 + C.n_arm
    for _ in range(10):
        q, qd = rng.normal(0.0, 0.3, n), rng.normal(0.0, 0.5, n)
        q[2] += 1.3
        for K, args in ((c.KE, (q, qd)), (backends.PYTHON, (list(q), list(qd)))):
            p, v, Rt, w = K.tip_frame(C, *args)
            assert (p, v) == tuple(K.tip_state(C, *args))
            Rm, wm = K.tip_motion(C, *args, [0.0] * n if K is backends.PYTHON
                                  else np.zeros(n))[:2]
            assert tuple(map(tuple, Rt)) == tuple(map(tuple, Rm)) and tuple(w) == tuple(wm)
