"""The long calls release the GIL, so Python threads run while the C++ library works.

The check does not time anything. With the interpreter's switch interval set far above any
call's duration, the main thread never gives up the GIL on its own: a thread waiting for it runs
during a call only if the call releases it. The thread is woken just before the call and notes
whether the call was still running when it got the GIL. A call that keeps the GIL
(symembed.stages) is the control: there the thread only runs after the call returned.
"""

import sys
import threading

import symembed
from conftest import PAIR_OPTIONS


def ran_during(call):
    """Whether a thread woken just before call() got the GIL while call() was running."""
    state = {"in_call": False, "seen": None}
    go = threading.Event()

    def observe():
        go.wait()
        state["seen"] = state["in_call"]

    thread = threading.Thread(target=observe)
    thread.start()
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        state["in_call"] = True
        go.set()
        call()
        state["in_call"] = False
    finally:
        sys.setswitchinterval(interval)
    thread.join()
    assert state["seen"] is not None
    return state["seen"]


def test_a_call_that_keeps_the_gil_is_seen_as_such():
    assert not ran_during(symembed.stages)


def test_match_of_arrays_releases_the_gil(pair):
    assert ran_during(lambda: symembed.match(pair.VA, pair.FA, pair.VB, pair.FB, PAIR_OPTIONS))


def test_match_of_shapes_releases_the_gil(shapes):
    assert ran_during(lambda: symembed.match(*shapes))


def test_shape_releases_the_gil(pair):
    assert ran_during(lambda: symembed.Shape(pair.VA, pair.FA, PAIR_OPTIONS))


def test_geodesic_errors_release_the_gil(pair, shapes):
    assert ran_during(
        lambda: symembed.geodesic_errors(shapes[1], pair.cli_map, pair.gt_a, pair.gt_b))


def test_run_releases_the_gil(pair, tmp_path):
    assert ran_during(
        lambda: symembed.run(pair.config, tmp_path / "out", cache="", quiet=True, report=False))
