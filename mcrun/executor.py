"""Where a batch of independent tasks runs: the one executor of every batch of shots.

A run's chunks, the start points of ``mcrun.run.starts``, the aims of ``mcrun aim``, the jobs of
a solve (``mcrun.play``: its actions flown from its states), its sweeps and the bands of a
green's map are each a list of tasks that do not depend on one another. They run here, and
nowhere else owns a pool of threads or a loop over Dask futures:

- ``on_threads(work, tasks)``: ``work(k)`` for every k on the threads of this process (the
  kernels': ``pool()``), each thread taking the next k until none is left. The work
  should release the GIL (a ``nogil`` kernel, NumPy on large arrays) to run at once.
- ``Executor.map(task, items, done=...)``: ``task(*shared, item)`` for every item, on this
  process's threads (``Executor(threads=T)``) or on the workers of a Dask client
  (``Executor(client=c)``: the ``shared`` objects sent to every worker once, each task on one
  Numba thread), ``done(k, result)`` as each finishes, in whatever order, progress said as
  they do.

A task that runs on a thread of the pool runs the kernels it calls on that thread alone
(``on_threads`` inside it is a plain loop): a batch of tasks keeps every thread busy with
tasks, not with halves of one. Whatever the threads, the workers or the order the tasks
finish in, each task's result is its own: a caller that puts the results in their places
(``done``) gets the same arrays, bit for bit.

Ctrl-C (or SIGTERM): the threads finish the task they hold and take no other; the Dask
futures are cancelled. A task that raises: the others still running finish, none is taken
after it, and its error is raised here (``TaskFailed`` on Dask, naming the task).

In the foundation layer (it imports no other part of mcrun but ``exits``), so that every layer
runs its batches here: the engine's shots (``engine.batch.simulate_batch``: its tasks on this
pool), a green's map (``putting.green_map``), the runs' starts and aims (``run``) and a solve
(``play``).
"""

import concurrent.futures
import secrets
import threading

import numba

from mcrun import exits

__all__ = [
    "NUMBA_THREADS_PER_TASK",
    "Executor",
    "TaskFailed",
    "in_background",
    "in_task",
    "on_threads",
    "pool",
]

# A Dask worker runs one task on each of its threads, each task's kernels on this many.
NUMBA_THREADS_PER_TASK = 1
_POOL = []
_BACKGROUND = []
_LOCAL = threading.local()


class TaskFailed(RuntimeError):
    """A task of a batch on Dask failed (after its retries): which, and why."""


def pool():
    """The pool of threads the batches run on, as many as Numba may use (made once)."""
    if not _POOL:
        _POOL.append(
            concurrent.futures.ThreadPoolExecutor(
                max_workers=numba.config.NUMBA_NUM_THREADS, thread_name_prefix="mcrun-kernel"
            )
        )
    return _POOL[0]


def in_background(fn, *args):
    """``fn(*args)`` on the one thread beside the pool (a stage that must take the results of
    a batch of tasks in order, as a run's writer does); a ``concurrent.futures.Future``."""
    if not _BACKGROUND:
        _BACKGROUND.append(
            concurrent.futures.ThreadPoolExecutor(max_workers=1, thread_name_prefix="mcrun-writer")
        )
    return _BACKGROUND[0].submit(fn, *args)


def in_task():
    """Whether this thread is running a task of ``on_threads`` (its kernels run on it alone)."""
    return getattr(_LOCAL, "task", False)


def on_threads(work, tasks, threads=None):
    """``work(k)`` for every k in range(``tasks``) on ``threads`` threads (default
    ``numba.get_num_threads()``) of the pool, each thread taking the next k until none is left;
    on this thread alone when one thread (and so are the kernels the tasks call), one task, or
    when this thread is itself running a task. ``work`` should release the GIL and the tasks
    be independent: then neither the thread count nor their order changes a bit."""
    count = numba.get_num_threads() if threads is None else int(threads)
    if count <= 1 and not in_task():  # one thread: what the tasks call runs on it alone too
        _LOCAL.task = True
        try:
            for k in range(tasks):
                work(k)
        finally:
            _LOCAL.task = False
        return
    if min(count, tasks) <= 1 or in_task():
        for k in range(tasks):
            work(k)
        return
    count = min(count, tasks)
    todo = iter(range(tasks))
    lock = threading.Lock()
    stopped = threading.Event()

    def take():
        _LOCAL.task = True
        try:
            while not stopped.is_set():
                with lock:
                    k = next(todo, None)
                if k is None:
                    return
                try:
                    work(k)
                except BaseException:
                    stopped.set()  # the others take no further task
                    raise
        finally:
            _LOCAL.task = False

    running = []
    try:
        # The pool starts its threads as work is submitted. Ctrl-C or SIGTERM while a thread
        # starts would leave that thread out of the pool's list, and the interpreter would wait
        # for it forever at exit: they wait until the threads have started.
        with exits.interrupts_deferred():
            running.extend(pool().submit(take) for _ in range(count))
        for each in running:
            each.result()
    finally:  # (Ctrl-C: the threads finish the task they hold, and take no other)
        stopped.set()
        concurrent.futures.wait(running)


class Executor:
    """Runs a batch of independent tasks on this process's threads or on a Dask cluster.

    ``threads``: the threads of this process (default ``numba.get_num_threads()``); ``client``:
    a ``dask.distributed.Client`` whose workers run the tasks instead (``retries`` each).
    """

    def __init__(self, threads=None, client=None, retries=0):
        self.threads = numba.get_num_threads() if threads is None else int(threads)
        self.client = client
        self.retries = int(retries)
        self._lock = threading.Lock()

    @property
    def on_dask(self):
        return self.client is not None

    def map(self, task, items, shared=(), done=None, progress=None, failed=None, name="task",
            key=None):  # fmt: skip
        """``task(*shared, item)`` for every item of ``items``; ``done(k, result)`` as the k-th
        finishes (in any order, one at a time: on this thread on Dask, on the task's thread
        under a lock here), else the results returned in order. ``progress(count)``: called
        with the tasks finished so far. ``name``: what a task is called in an error ("job",
        "aim"). On Dask: ``failed(k, error)`` for each task that failed after its retries (the
        others go on; without it the first failure raises ``TaskFailed``), ``key``: the
        tasks' key prefix (the dashboard's name for them)."""
        items = list(items)
        results = None if done is not None else [None] * len(items)

        def put(k, result):
            if done is None:
                results[k] = result
            else:
                done(k, result)

        if self.client is None:
            self._local(task, items, shared, put, progress)
        else:
            self._dask(task, items, shared, put, progress, failed, name, key)
        return results

    def _local(self, task, items, shared, put, progress):
        count = [0]

        def work(k):
            result = task(*shared, items[k])
            with self._lock:  # one result put at a time, and the progress said in order
                put(k, result)
                count[0] += 1
                if progress is not None:
                    progress(count[0])

        on_threads(work, len(items), self.threads)

    def _dask(self, task, items, shared, put, progress, failed, name, key):
        from distributed import Future, as_completed

        client = self.client
        prefix = key or f"mcrun-{name.replace(' ', '-')}-{secrets.token_hex(4)}"
        # The shared objects travel once, each as a task of its own (so that a worker that
        # lost it computes it again), which every task depends on; a future given is one.
        there = [obj if isinstance(obj, Future)
                 else client.submit(_itself, obj, key=f"{prefix}-shared-{j}", pure=False)
                 for j, obj in enumerate(shared)]  # fmt: skip
        futures = [client.submit(_on_worker, task, *there, item, key=f"{prefix}-{k:05d}",
                                 retries=self.retries, pure=False)
                   for k, item in enumerate(items)]  # fmt: skip
        index = {future.key: k for k, future in enumerate(futures)}
        try:
            for finished, future in enumerate(as_completed(futures), start=1):
                k = index[future.key]
                if future.status == "finished":
                    put(k, future.result())
                else:
                    err = future.exception() if future.status == "error" else None
                    err = err or RuntimeError(f"the task was {future.status}")
                    if failed is None:
                        raise TaskFailed(
                            f"{name} {k} of {len(items)} failed"
                            + (f" after {self.retries} retries" if self.retries else "")
                            + f": {' '.join(f'{type(err).__name__}: {err}'.split())}"
                        ) from err
                    failed(k, err)
                future.release()
                if progress is not None:
                    progress(finished)
        except BaseException:
            client.cancel([*futures, *there])
            raise
        finally:
            for each in there:
                each.release()


def _itself(obj):
    """A shared object of a batch on Dask, as a task."""
    return obj


def _on_worker(task, *args):
    """A task on a Dask worker, on ``NUMBA_THREADS_PER_TASK`` Numba threads."""
    numba.set_num_threads(NUMBA_THREADS_PER_TASK)
    return task(*args)
