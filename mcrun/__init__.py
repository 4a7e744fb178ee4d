"""mcrun: a Numba Monte Carlo engine for golf shots (flight, Penner 2002 bounce, roll)."""

from mcrun.api import InputError, ShotResult, bounce_once, simulate

__version__ = "0.1.0"
__all__ = ["InputError", "ShotResult", "bounce_once", "simulate", "__version__"]
