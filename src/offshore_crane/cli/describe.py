"""``offshore-crane describe``: a robot description, resolved and checked, as the YAML the
xacro reads.

Prints (or writes with ``--out``) every number of the robot after the overrides and the
expressions are applied, in the form ``models/offshore_crane.urdf.xacro`` reads: to
expand the xacro by hand, ``xacro models/offshore_crane.urdf.xacro description:=$PWD/F.yaml``.
"""

from __future__ import annotations


def add_parser(sub) -> None:
    from offshore_crane.cli.common import add_robot_options

    doc = __doc__.splitlines()
    p = sub.add_parser("describe", help="a robot description, resolved, as YAML",
                       description=doc[0].split(": ", 1)[1] + " " + " ".join(
                           line.strip() for line in doc[2:5]))
    add_robot_options(p)
    p.add_argument("--out", help="write the YAML to this file ('-' or none: standard "
                   "output)")
    p.set_defaults(run=run)


def run(args) -> int:
    from offshore_crane.io import plan_outputs, write_text
    from offshore_crane.robot.description import resolve
    from offshore_crane.robot.overrides import parse_set
    from offshore_crane.robot.xacro_cache import description_yaml

    outputs = plan_outputs({"--out": args.out or "-"}, [args.robot])
    text = description_yaml(resolve(args.robot, parse_set(args.set)).xacro_data())
    write_text(outputs["--out"], text)
    if outputs["--out"].kind != "stdout":
        print(f"wrote {args.out}")
    return 0
