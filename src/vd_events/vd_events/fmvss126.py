"""
FMVSS 126 sine-with-dwell grading for measured logs and simulations alike.

The one implementation is :mod:`vd_solvers.fmvss126` (the full-vehicle solver runs the
procedure with it); this module names it where the event tools look for it.
"""
from vd_solvers.fmvss126 import *  # noqa: F401,F403
from vd_solvers.fmvss126 import __all__  # noqa: F401
