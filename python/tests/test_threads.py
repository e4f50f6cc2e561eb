"""Long computations release the GIL: while a diagnosis runs in one Python
thread, another keeps running Python code. Held, the second thread would stop
for the whole call (it could only run in the few milliseconds before the call
takes the GIL)."""

import threading
import time

import femup
from conftest import EXAMPLES


def spin_rate(seconds=0.2):
    """Loop iterations per second of this thread alone."""
    ticks, end = 0, time.perf_counter() + seconds
    while time.perf_counter() < end:
        ticks += 1
    return ticks / seconds


def test_a_diagnosis_runs_while_python_keeps_running():
    study = femup.load_study(str(EXAMPLES / "diagnosis" / "added_mass.yaml"))
    rate = spin_rate()
    done = threading.Event()
    result = {}

    def work():
        try:
            result["diagnosis"] = femup.diagnose(study)
        finally:
            done.set()  # also when it raises: the loop below must end

    worker = threading.Thread(target=work)
    start = time.perf_counter()
    worker.start()
    ticks = 0
    while not done.is_set() and time.perf_counter() - start < 300:
        time.perf_counter()  # the same work per iteration as the calibration
        ticks += 1
    elapsed = time.perf_counter() - start
    worker.join()
    assert result.get("diagnosis") is not None, "the diagnosis ran"
    assert elapsed > 0.3, "too short a call to tell (%.2f s)" % elapsed
    # Released: this thread ran through most of the call; held: ~5 ms of it.
    share = ticks / (rate * elapsed)
    assert share > 0.1, "Python ran %.1f %% of a %.2f s call" % (100 * share, elapsed)


def test_the_blas_runs_one_thread_per_call():
    # femup parallelises above the BLAS (its results do not depend on the
    # number of threads), so importing it sets the BLAS to one thread per call.
    summary = femup.blas()
    assert summary.startswith("BLAS: ")
    if "OpenBLAS" in summary:
        assert ", 1 thread per call" in summary, summary
