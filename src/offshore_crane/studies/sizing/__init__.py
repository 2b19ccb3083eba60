"""Actuator sizing: the envelope of one run against the actuators' capacities, and the
most probable maximum of a random sea from several seeds (pure NumPy).

An **envelope** (:func:`envelope`) condenses one run ``(t, q, q̇, X)`` into, per actuator
of ``X = [T1, T2, Fs, Fl1..Fl6]`` (``docs/conventions.md``):

- the peak push ``max(X, 0)`` and the peak pull ``max(−X, 0)`` [N·m or N], each with its
  time [s]; the RMS of X;
- the peak speed ``max |v|`` of the actuator's joint: ``q̇7, q̇8`` [rad/s], ``q̇9`` [m/s],
  the leg rates ``l̇_i`` [m/s] (:func:`offshore_crane.robot.kinematics.legs`);
- the peak power ``max |X v|`` and the mean absolute power ``mean |X v|`` [W];
- the stroke used: min and max of the joint position (q7, q8 [rad], q9 [m], leg length
  l_i [m]);
- the utilisation of each capacity of :attr:`offshore_crane.robot.Robot.capacities`:
  ``push = peak push / push_max``, ``pull``, ``speed``, ``power`` likewise, and
  ``stroke = max |p − mid| / half`` over the joint's range ``[lo, hi]`` (the legs' stroke,
  the arm joints' limits, from the robot description): 1 means the motion reaches an end.
  A capacity the description does not give (``inf``) has utilisation NaN ("no limit"),
  never 0.

and for the run: the worst condition number of each singularity kind (leg Jacobian,
U-joint gimbal, attitude) with its time, the worst utilisation with the actuator and
the capacity that govern it, and with a payload on a cable (:mod:`offshore_crane.dynamics.cable`)
the largest sway from the tip's vertical [rad] and the smallest and largest cable
tension [N] (NaN without a cable).

For a random sea a single record's peak is itself random. :func:`verdict` takes the
envelopes of the same case under several seeds, each a stationary record as long as the
exposure (3 hours full scale by default: :mod:`offshore_crane.scenes.exposure`): with at
least :data:`MIN_SEEDS` of them it fits a Gumbel distribution to the per-record maxima
of every peak quantity by maximum likelihood (:func:`gumbel_fit`), and the most probable
maximum of the exposure is the fit's mode μ (:func:`most_probable_maximum` with one
record per exposure). With fewer records, or records shorter than the exposure
(:func:`covers_exposure`), no fit is made: the verdict rests on the largest observed
peak and says why (its ``basis``, :meth:`Verdict.describe`). ``docs/sizing.md`` has the
formulas and the choices."""

from __future__ import annotations

from offshore_crane.lazy import submodule_getattr

from offshore_crane.robot.kinematics import actuator_motion
from offshore_crane.studies.sizing.envelopes import (CAPACITIES, QUANTITIES, KINDS,
                                                     POSITION_UNITS, SPEED_UNITS, Envelope,
                                                     row_columns, stroke_ranges,
                                                     envelope, conditions)
from offshore_crane.studies.sizing.loads import (LIFT, LOAD_CRITERIA, WINCH_DEMANDS,
                                                 load_utilisation, slack_utilisation)
from offshore_crane.studies.sizing.extremes import (MIN_SEEDS, EXPOSURE, covers_exposure,
                                                    gumbel_fit, most_probable_maximum,
                                                    most_probable_extreme)
from offshore_crane.studies.sizing.verdicts import Verdict, verdict
from offshore_crane.studies.sizing.formatting import format_envelope, format_verdict


#: Sub-modules load on first use, as attributes (:mod:`offshore_crane.lazy`).
__getattr__ = submodule_getattr(__name__)
