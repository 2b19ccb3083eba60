"""The built-in laws' codes in the compiled rigid-robot loop (:mod:`offshore_crane.
simulation.rk4`): one enumeration, so that a law added to the loop takes the next free
code and none collides. ``SHARED`` is computed torque on the plant's own model with one
explicit pass a stage serving both the law and the accelerations."""

COMPUTED_TORQUE, PD_GRAVITY, PD, NONE, SHARED = range(5)
