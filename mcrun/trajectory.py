"""Recording a shot's path into a preallocated buffer (time, x, y, z, phase) inside the kernel.

Rows are in the user's frame (y to the right). A zero-row buffer records nothing; so does no
buffer (None), the batch kernels' case, where the recording is pruned from the compiled code.
"""

from numba import njit

FLIGHT = 0
BOUNCE = 1
ROLL = 2
PHASE_NAMES = ("flight", "bounce", "roll")


@njit(cache=True)
def record(traj, n, t, x, y, z, phase):
    """Write one point (core frame in, user frame out) at row n; return the next row."""
    if traj is None:
        return n + 1
    if n < traj.shape[0]:
        traj[n, 0] = t
        traj[n, 1] = x
        traj[n, 2] = -y
        traj[n, 3] = z
        traj[n, 4] = phase
    return n + 1
