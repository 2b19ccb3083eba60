"""The built-in laws' codes in the compiled rigid-robot law
(:func:`offshore_crane.simulation.rigid_equations.law`, which the rigid plant's inverse
dynamics and the DOP853 reference path call): one enumeration, so that a law added to it
takes the next free code and none collides."""

COMPUTED_TORQUE, PD_GRAVITY, PD, NONE = range(4)
