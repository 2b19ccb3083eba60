"""The command line, called in-process through main(argv) and once as a real process."""

import subprocess
import sys

import numpy as np
import pytest

from offshore_crane.__main__ import main


def test_id_table1_summary(capsys):
    assert main(["id", "--trajectory", "table1", "--duration", "5"]) == 0
    out = capsys.readouterr().out
    assert "501 samples" in out
    for name in ("T1", "T2", "Fs", "Fl1", "Fl6"):
        assert f"\n{name} " in out


def test_id_both_writes_csv_and_plot(tmp_path, capsys):
    csv, png = tmp_path / "x.csv", tmp_path / "x.png"
    code = main(["id", "--method", "both", "--duration", "3", "--rate", "50",
                 "--out", str(csv), "--plot", str(png)])
    assert code == 0
    out = capsys.readouterr().out
    assert "Kane vs RNEA" in out and "(OK, limit 1e-09)" in out
    header = csv.read_text().splitlines()[0]
    assert header == "t_s,T1_Nm,T2_Nm,Fs_N,Fl1_N,Fl2_N,Fl3_N,Fl4_N,Fl5_N,Fl6_N"
    data = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert data.shape == (151, 10)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_id_to_standard_output(capsys):
    """``--out -``: the CSV alone on standard output, the summary on standard error (once
    a NameError: the path no test took)."""
    assert main(["id", "--duration", "0.1", "--out", "-"]) == 0
    captured = capsys.readouterr()
    lines = captured.out.splitlines()
    assert lines[0] == "t_s,T1_Nm,T2_Nm,Fs_N,Fl1_N,Fl2_N,Fl3_N,Fl4_N,Fl5_N,Fl6_N"
    assert len(lines) == 12 and "offshore-crane id:" in captured.err


def test_negative_pose_lists_and_a_wrote_line_for_every_file(tmp_path, capsys):
    """A comma list starting with a minus (``--pose -0.01,...``) is a value, not an
    option; every command that writes a file says so ("wrote ...")."""
    png, yaml, xml = tmp_path / "p.png", tmp_path / "d.yaml", tmp_path / "m.xml"
    assert main(["show", "--pose", "-0.01,0,0.6,0,0,0,0,0,0", "--out", str(png)]) == 0
    assert main(["describe", "--out", str(yaml)]) == 0
    assert main(["export", "--pose", "-0.01,0,0.6,0,0,0,0,0,0", "--mjcf", str(xml)]) == 0
    out = capsys.readouterr().out
    for path in (png, yaml, xml):
        assert path.is_file() and f"wrote {path}" in out


def test_method_comparison_names_the_actuator(capsys):
    assert main(["id", "--method", "both", "--duration", "1", "--rate", "50"]) == 0
    out = capsys.readouterr().out
    line = next(ln for ln in out.splitlines() if ln.startswith("Kane vs RNEA"))
    assert "column" not in line
    assert any(f", {name})" in line for name in ("T1", "T2", "Fs", "Fl1", "Fl2", "Fl3",
                                                   "Fl4", "Fl5", "Fl6"))


def test_id_from_csv(tmp_path, capsys):
    from offshore_crane.motion import trajectories

    t = np.arange(0, 2.0, 0.01)
    q, _, _ = trajectories.table1(t)
    path = tmp_path / "traj.csv"
    trajectories.write_csv(path, t, q)
    assert main(["id", "--trajectory", str(path), "--fd-order", "6"]) == 0
    assert "200 samples" in capsys.readouterr().out


@pytest.mark.parametrize("argv, match", [
    (["id", "--set", "platfrom_mass=3"], "unknown robot parameter 'platfrom_mass'"),
    (["id", "--set", "platform_mass"], "--set expects name=value"),
    (["id", "--trajectory", "table2"], "unknown trajectory 'table2'"),
    (["id", "--rate", "-5"], "rate"),
])
def test_errors_are_one_line_exit_2(argv, match, capsys, tmp_path):
    out = tmp_path / "never.csv"
    assert main(argv + ["--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("offshore-crane: error: ") and match in err
    assert err.count("\n") == 1
    assert not out.exists()


def test_kane_run_imports_neither_pinocchio_nor_matplotlib():
    code = ("import sys; from offshore_crane.__main__ import main; "
            "assert main(['id', '--duration', '1']) == 0; "
            "bad = [m for m in ('pinocchio', 'matplotlib', 'yourdfpy', 'viser', 'imageio', "
            "'imageio_ffmpeg', 'mujoco', 'PIL', 'selenium') if m in sys.modules]; "
            "assert not bad, bad")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)


def test_console_script_no_traceback():
    proc = subprocess.run([sys.executable, "-m", "offshore_crane", "id", "--trajectory",
                           "nope.csv"], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and "unknown trajectory 'nope.csv'" in proc.stderr
