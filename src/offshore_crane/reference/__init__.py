"""Reference paths that share only the URDF with what they check.

- :mod:`.rnea`: Pinocchio's RNEA on the equivalent tree, with loop-closing tree states
  of its own (inverse dynamics, ``method="rnea"``).
"""
