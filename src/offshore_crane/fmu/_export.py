"""Writing a scene's crane as an FMI 2.0 co-simulation FMU (:func:`export_fmu`), built
by PythonFMU: its model is :class:`~offshore_crane.fmu.model.CraneSlave`, whose
simulation runs in a process of its own (:mod:`offshore_crane.fmu._worker`)."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

from offshore_crane.errors import InputError, require
from offshore_crane.fmu import model as crane_model

#: The FMU's model name (its ``modelIdentifier``: the binaries' name).
MODEL = "OffshoreCrane"
#: What follows the model's text (:mod:`offshore_crane.fmu.model`) in the FMU's script:
#: the class the FMU names, with the run's default experiment (``{start}``, ``{stop}``,
#: ``{step}`` [s]).
SCRIPT_END = '''

# ---------------------------------------------------------- written by export --fmu
from pythonfmu import DefaultExperiment  # noqa: E402

# PythonFMU's loader runs this text again at each instantiation with this module's
# dictionary as globals, then releases that dictionary once more than it took it (its
# findClass: Py_DECREF of PyModule_GetDict's borrowed reference): a process that frees
# an instance and goes on would use the freed dictionary. Each run keeps one more
# reference to it here, which that release takes back.
globals().setdefault("_KEPT", []).append(globals())


class {model}(CraneSlave):
    description = {description!r}
    default_experiment = DefaultExperiment(start_time={start!r}, stop_time={stop!r},
                                           step_size={step!r})
'''


def export_fmu(scene, target, *, control_period: float, duration: float | None = None,
               action: str = "forces") -> Path:
    """Write ``scene``'s crane as an FMU.

    Args:
        scene: A scene file's path (the scene and the files it reads go into the FMU).
        target: The FMU's path (``.fmu``), or a :class:`~offshore_crane.io.Target`.
        control_period: [s] the FMU's communication step (a whole number of the scene's
            integration steps); a master may step any whole number of them at once.
        duration: [s] the run (default: the scene's, in whole periods).
        action: The inputs: ``"forces"`` or ``"reference"`` (as the stepper's).

    Returns:
        The FMU's path.

    Raises:
        InputError, SceneError: what the scene or the stepper refuses; an FMU path that
            is one of the scene's inputs or not ``.fmu``; a scene's data file outside the
            scene's folder (the FMU keeps the folder's layout).
    """
    from offshore_crane import scenes
    from offshore_crane.io import Target, plan_outputs, write_bytes

    builder = require("pythonfmu.builder", '"offshore-crane[fmu]"', "export --fmu")
    if not isinstance(scene, (str, os.PathLike)):
        raise InputError(f"scene = {scene!r}: give the scene file's path (the FMU holds "
                         "the file)", name="scene")
    sc = scenes.load_scene(scene)
    if not isinstance(target, Target):
        target = plan_outputs({"--fmu": target}, sc.inputs(), {"--fmu": ("fmu",)})["--fmu"]
    sim = scenes.stepper(sc, control_period=control_period, duration=duration,
                         action=action)
    t0 = float(sim.plan()[0][0])
    settings = _settings(sc, sim, control_period, action)
    with tempfile.TemporaryDirectory(prefix="oc-fmu-") as tmp:
        tmp = Path(tmp)
        folder = tmp / crane_model.FOLDER
        _copy_scene(sc, Path(scene), folder)
        (folder / "settings.json").write_text(json.dumps(settings, indent=1))
        digest = hashlib.sha256(json.dumps(settings, sort_keys=True).encode()
                                + b"".join(p.read_bytes() for p in sorted(
                                    folder.rglob("*")) if p.is_file())).hexdigest()[:16]
        script = tmp / f"offshore_crane_fmu_{digest}.py"
        model = Path(crane_model.__file__).read_text(encoding="utf-8")
        script.write_text(model + SCRIPT_END.format(
            model=MODEL, description=f"{sc.name}: {sc.description}".strip(": "),
            start=t0, stop=t0 + settings["duration"], step=float(control_period)))
        try:
            built = builder.FmuBuilder.build_FMU(
                script, dest=tmp / "build", project_files=[folder],
                canHandleVariableCommunicationStepSize=False)
        finally:
            sys.modules.pop(script.stem, None)   # a later export's module is its own
            if str(tmp) in sys.path:
                sys.path.remove(str(tmp))
        write_bytes(target, Path(built).read_bytes())
    return Path(target.path)


def _settings(scene, sim, control_period: float, action: str) -> dict:
    """What the FMU's model reads at its start (``settings.json``)."""
    plan = sim.plan()[0]
    params = {}
    if scene.trajectory == "sea":
        params.update({k: float(scene.sea[k]) for k in ("hs", "tp", "heading")
                       if k in scene.sea})
    if scene.payload.mass > 0.0:
        params["payload_mass"] = float(scene.payload.mass)
    start = sim.reset()
    names = sim.observation_names
    action_start = (sim.holding().tolist() if action == "forces" else           # the scene's
                    [float(start[names.index(n.replace("_cmd_", "_ref_"))])   # reference
                     for n in sim.action_names])
    return {"scene": Path(scene.path).name, "control_period": float(control_period),
            "duration": float(plan[-1] - plan[0]), "action": action,
            "seed": int(scene.sea.get("seed", 0)) if scene.trajectory == "sea" else 0,
            "parameters": params, "action_names": list(sim.action_names),
            "action_start": action_start, "observation_names": list(names)}


def _copy_scene(scene, path: Path, folder: Path) -> None:
    """The scene file and the files it reads into ``folder`` at their places relative to
    the scene's (the shipped default description stays in the package)."""
    from offshore_crane.robot.description import default_description

    base = path.resolve().parent
    folder.mkdir()
    shutil.copy2(path, folder / path.name)
    default = Path(default_description()).resolve()
    for name in scene.data_files():
        src = Path(name).resolve()
        if src == default:
            continue
        try:
            rel = src.relative_to(base)
        except ValueError:
            raise InputError(f"the scene's file {name} is outside the scene's folder "
                             f"{base}: the FMU keeps the files at their places relative "
                             "to the scene; move it into that folder", name="scene") from None
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, folder / rel)
