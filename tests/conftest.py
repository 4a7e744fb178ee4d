"""Fixtures shared by several test files."""

import signal

import pytest


@pytest.fixture
def ctrl_c_raises():
    """SIGINT raises KeyboardInterrupt during the test, as in a terminal, even where the suite
    was started with SIGINT ignored (a job put in the background by a non-interactive shell
    inherits it ignored, and Python then installs no handler of its own)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)
