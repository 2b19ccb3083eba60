import numpy as np
import pytest

import offshore_crane as oc
from offshore_crane import trajectories


@pytest.fixture(scope="session")
def robot():
    return oc.load_robot()


@pytest.fixture(scope="session")
def table1():
    """Default Table 1 span: t (3142,), q, qd, qdd (3142, 9)."""
    t = trajectories.time_grid()
    return (t, *trajectories.table1(t))


def relative_error(X, Y) -> float:
    """max |X - Y| / max |Y|."""
    return float(np.abs(np.asarray(X) - np.asarray(Y)).max() / np.abs(np.asarray(Y)).max())
