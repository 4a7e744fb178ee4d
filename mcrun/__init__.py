"""mcrun: a Numba Monte Carlo engine for golf shots (flight, Penner 2002 bounce, roll).

The one-shot API (``simulate``, ``bounce_once``, ``ShotResult``) is imported on first use, so
that importing the package starts no Numba: the command line checks its environment first
(``mcrun.exits.environment_problem``)."""

from mcrun.errors import InputError

__version__ = "0.1.0"
__all__ = ["InputError", "ShotResult", "bounce_once", "simulate", "__version__"]
_API = ("ShotResult", "bounce_once", "simulate")


def __getattr__(name):
    if name in _API:
        from mcrun.exits import environment_problem

        problem = environment_problem()  # (Numba's ValueError at its import, or its silence)
        if problem:
            raise InputError(problem)
        from mcrun import api

        # Checked once: later uses find them here (the check probes NUMBA_CACHE_DIR's folder).
        globals().update({api_name: getattr(api, api_name) for api_name in _API})
        return getattr(api, name)
    raise AttributeError(f"module 'mcrun' has no attribute {name!r}")


def __dir__():
    return sorted({*globals(), *_API})
