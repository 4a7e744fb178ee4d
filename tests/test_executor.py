"""The one executor of every batch of tasks (``mcrun.executor``): results in their places
whatever the threads, one result put at a time, a failed task's error raised with no task taken
after it, and a task's own kernels on its thread."""

import threading
import time

import numba
import pytest

from mcrun import executor
from mcrun.executor import Executor, in_task, on_threads


def test_the_results_come_back_in_their_places_whatever_the_threads():
    """Tasks that finish out of order (the first sleeps longest) still return in item order,
    each computed from the shared arguments and its item."""

    def task(scale, offset, item):
        time.sleep(0.002 * (8 - item))
        return scale * item + offset

    for threads in (1, 2, 4):
        assert Executor(threads=threads).map(task, range(8), shared=(10, 1)) == [
            10 * k + 1 for k in range(8)
        ]


def test_done_is_called_once_a_task_one_at_a_time_and_progress_counts_them():
    seen, inside, most = [], [0], [0]
    counts = []

    def done(k, result):
        inside[0] += 1
        most[0] = max(most[0], inside[0])
        time.sleep(0.001)
        seen.append((k, result))
        inside[0] -= 1

    Executor(threads=2).map(lambda x: x * x, range(20), done=done, progress=counts.append)
    assert sorted(seen) == [(k, k * k) for k in range(20)]
    assert most[0] == 1  # never two at once
    assert counts == list(range(1, 21))


def test_a_failed_task_raises_its_error_and_no_task_is_taken_after_it():
    started = []
    lock = threading.Lock()

    def task(item):
        with lock:
            started.append(item)
        if item == 3:
            raise ArithmeticError("task 3")
        time.sleep(0.01)
        return item

    with pytest.raises(ArithmeticError, match="task 3"):
        Executor(threads=2).map(task, range(50))
    # The thread that failed took no other; the other finished the one it held.
    assert len(started) <= 6


def test_a_task_runs_its_kernels_on_its_own_thread():
    """Inside a task, ``on_threads`` is a loop on the task's thread (a batch of tasks keeps the
    threads busy with tasks, not with halves of one); on one thread, the kernels run on it."""
    names = []

    def task(item):
        assert in_task()
        on_threads(lambda k: names.append(threading.current_thread().name), 4, threads=2)
        return item

    Executor(threads=2).map(task, range(3))
    assert len(names) == 12
    one = []
    on_threads(lambda k: one.append((in_task(), threading.current_thread().name)), 3, threads=1)
    assert one == [(True, threading.current_thread().name)] * 3
    assert not in_task()


def test_the_pool_is_one_and_as_large_as_numba_may_use():
    assert executor.pool() is executor.pool()
    assert executor.pool()._max_workers == numba.config.NUMBA_NUM_THREADS
