"""Convert the MSS toolbox's supply-vessel motion RAOs to offshore-crane's long-form CSV.

Source (MIT licence, Copyright (c) 2004 Thor I. Fossen): the MSS toolbox,
https://github.com/cybergalactic/MSS, commit 736a3d128ccd5ecb3736eba231bbf046de7bdafa,
file ``HYDRO/vessels_shipx/supply/supply.mat`` (variable ``vessel``). The RAOs were
computed by ShipX/VERES (strip theory) for a supply vessel with Lpp 82.8 m, beam 19.2 m,
draught 6.0 m, and read into MSS by ``HYDRO/veres2vessel.m`` / ``read_veres_TF.m``.

Usage (no download: give the path of the extracted ``supply.mat``)::

    python scripts/convert_mss_raos.py PATH/TO/supply.mat \\
        [--out src/offshore_crane/motion/data/vessels/supply.csv]

What the MSS structure holds (checked by this script): ``vessel.motionRAO.w`` (36
frequencies [rad/s]), ``vessel.headings`` (36 headings [rad], 0:10:350 deg; MSS mirrored
VERES's 0..180 deg to 190..350 deg by port-starboard symmetry), ``vessel.velocities``
(only 0 m/s is filled; the speed axis has 10 slots, the others zero), and for each DOF
``vessel.motionRAO.amp{dof}(w, heading, speed)`` [m/m, rad/m] and ``.phase`` [rad].

Conventions of MSS (read in ``waveMotionRAO.m`` and ``read_veres_TF.m``, and checked
against the long-wave limit below):

* axes forward-starboard-down (FSD): x to the bow, y to starboard, z down; roll about
  x (positive starboard down), pitch about y (positive bow up), yaw about z (positive
  bow to starboard);
* phase: ``waveMotionRAO.m`` synthesises the wave as ``A cos(w t + eps)`` and the
  response as ``|RAO| A cos(w t + angle(RAO) + eps)``: a phase *lead*, the same as ours;
* heading ``beta``: 0 = following seas, 180 deg = head seas (``waveMotionRAO.m``), and
  90 deg = waves travelling towards starboard, i.e. coming *from port* (the propagation
  direction ``(cos beta, sin beta)`` in forward-starboard axes).

Our conventions (``docs/sea.md``): axes x forward, y port, z up; roll positive starboard
down, pitch positive bow down, yaw positive bow to port; heading 180 = head seas, 90 deg
= waves *from starboard* (propagation ``(cos beta, sin beta)`` in forward-port axes);
response = ``amplitude * a * cos(w t + eps + phase)``.

The conversion is a rotation of pi about x: ``y -> -y``, ``z -> -z``. Hence

* sway, heave, pitch, yaw change sign (phase + pi, amplitude kept); surge, roll keep it;
* heading: ``beta_ours = (360 - beta_MSS) mod 360`` (a direction's y component flips);
* the phase convention is unchanged (both lead).

Checks made before writing (the script stops with a message if one fails): zero speed
is the first speed slot and the others hold no data; the long-wave limit
(w = 0.105 rad/s, wavelength 5.6 km) of the converted table agrees with a vessel that
follows the water surface: heave ~ +1, head-seas surge ~ +i (displacement against the
propagation, a quarter period ahead of the elevation), beam-seas (90 deg, from
starboard) sway ~ -i, and the signs of the pitch and roll slopes (pitch ~ +i k cos(beta),
roll ~ -i k sin(beta) times a positive factor; k = w^2/g). Numbers are written with 9 significant
digits (VERES's text files carry 8).

The RAO reference point (origin of the table) is VERES's motion point, read by MSS as
5.39 m aft of Lpp/2 on the centre line in the calm waterplane (``.re1`` header: xmtn
5.386 m, zmtn 6.0 m above the keel; MSS's ``vessel.main.CG`` = (-5.39, 0, 7.3) m).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: Sign of each DOF under the rotation of pi about x (FSD -> forward-port-up).
SIGN = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
HEADER = "omega_rad_s,heading_deg,dof,amplitude,phase_rad"
#: Gravity used by VERES for this vessel (.re1 header, vessel.main.g) [m/s^2].
G_VERES = 9.81
#: Long-wave checks: |RAO - limit| below this fraction of |limit| at the lowest frequency.
#: At w = 0.105 rad/s (k L = 0.09 over Lpp) the vessel follows the surface to ~1 %
#: in translations; the slopes (roll, pitch) are only checked for their sign and
#: direction (VERES's roll at this frequency is 1.6 k: the sway-roll coupling).
LONG_WAVE_TOL = 0.02


def load_mss(path: Path):
    """(omega (F,), heading_deg MSS (H,), H (F, H, 6) complex, main data dict)."""
    from scipy.io import loadmat

    mat = loadmat(str(path), squeeze_me=True, struct_as_record=False)
    vessel = mat["vessel"]
    rao = vessel.motionRAO
    velocities = np.atleast_1d(np.asarray(vessel.velocities, dtype=float))
    if velocities[0] != 0.0:
        sys.exit(f"{path}: the first speed is {velocities[0]} m/s, expected 0")
    omega = np.asarray(rao.w, dtype=float)
    heading = np.degrees(np.asarray(vessel.headings, dtype=float))
    H = np.empty((omega.size, heading.size, 6), dtype=complex)
    for d in range(6):
        amp = np.asarray(rao.amp[d], dtype=float)
        phase = np.asarray(rao.phase[d], dtype=float)
        if amp.shape[:2] != (omega.size, heading.size):
            sys.exit(f"{path}: {DOFS[d]} amplitudes have shape {amp.shape}, expected "
                     f"({omega.size}, {heading.size}, speeds)")
        if amp.ndim == 3 and velocities.size == 1 and np.any(amp[:, :, 1:]):
            sys.exit(f"{path}: {DOFS[d]} has data at speed slots the file does not list")
        H[:, :, d] = (amp[:, :, 0] if amp.ndim == 3 else amp) * np.exp(
            1j * (phase[:, :, 0] if phase.ndim == 3 else phase))
    main = {k: getattr(vessel.main, k) for k in ("Lpp", "B", "T", "CG", "g")}
    return omega, heading, H, main


def convert(omega, heading_mss, H_mss):
    """Our headings (sorted) and RAOs (F, H, 6) from MSS's."""
    heading = np.mod(360.0 - heading_mss, 360.0)
    heading = np.round(heading, 9)                    # 360 - 350.0000001 etc.
    order = np.argsort(heading)
    return heading[order], H_mss[:, order, :] * SIGN


def check_long_wave(omega, heading, H):
    """Stop unless the lowest frequency behaves as a vessel riding a long wave."""
    k = omega[0] ** 2 / G_VERES
    at = {h: i for i, h in enumerate(heading)}
    failures = []

    def near(value, target, what):
        if abs(value - target) > LONG_WAVE_TOL * abs(target):
            failures.append(f"{what}: {value:.4g}, expected about {target:.4g}")

    for h in (0.0, 90.0, 180.0, 270.0):
        near(H[0, at[h], 2], 1.0, f"heave at {h:g} deg")
    near(H[0, at[180.0], 0], 1j, "surge in head seas")
    near(H[0, at[0.0], 0], -1j, "surge in following seas")
    near(H[0, at[90.0], 1], -1j, "sway with waves from starboard")
    # slopes of zeta = a cos(w t + eps - k (x cos(beta) + y sin(beta))) at the origin:
    # pitch (bow down) = -d(zeta)/dx -> +i k cos(beta); roll = d(zeta)/dy -> -i k sin(beta)
    for h, dof, expect in ((180.0, 4, -1j), (0.0, 4, 1j), (90.0, 3, -1j), (270.0, 3, 1j)):
        value = H[0, at[h], dof] / k
        if not (value.imag * expect.imag > 0 and abs(value.real) < 0.1 * abs(value)):
            failures.append(f"{DOFS[dof]} at {h:g} deg: {value:.4g} k, expected a positive "
                            f"multiple of {expect} k")
    if failures:
        sys.exit("long-wave check failed: " + "; ".join(failures))


def write_csv(path: Path, omega, heading, H) -> int:
    rows = [HEADER]
    for j, h in enumerate(heading):
        for d, dof in enumerate(DOFS):
            for i, w in enumerate(omega):
                z = H[i, j, d]
                amp = abs(z)
                phase = math.atan2(z.imag, z.real) if amp > 0.0 else 0.0
                rows.append(f"{w:.9g},{h:.9g},{dof},{amp:.9g},{phase:.9g}")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return len(rows) - 1


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mat", type=Path, help="path of MSS's supply.mat")
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve().parents[1]
                        / "src" / "offshore_crane" / "data" / "vessels" / "supply.csv")
    args = parser.parse_args(argv)
    omega, heading_mss, H_mss, main_data = load_mss(args.mat)
    heading, H = convert(omega, heading_mss, H_mss)
    check_long_wave(omega, heading, H)
    n = write_csv(args.out, omega, heading, H)
    print(f"{args.out}: {n} rows, {omega.size} frequencies {omega[0]:.4g}..{omega[-1]:.4g} "
          f"rad/s x {heading.size} headings; Lpp {main_data['Lpp']:.1f} m, beam "
          f"{main_data['B']:.1f} m, draught {main_data['T']:.1f} m")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
