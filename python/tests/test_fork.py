"""The module in processes forked from one that used it (`multiprocessing` with the fork start
method, `os.fork`): the library's helper threads are the parent's and do not exist in a child,
and the parent's pool lock may be held at the fork. A child must compute the same answers and
never wait for them; each child here has a time limit that fails the test instead of hanging."""

import multiprocessing
import os
import sys
import threading

import pytest

import dqsym

from conftest import ROOT

PUMA = str(ROOT / "examples" / "robots" / "puma560.toml")

# A child that takes longer than this is waiting for something that will never come: the
# Jacobian takes well under a second here, even on a loaded machine.
LIMIT = 120

pytestmark = pytest.mark.skipif(
    sys.platform == "win32" or "fork" not in multiprocessing.get_all_start_methods(),
    reason="no fork on this platform",
)


def child_exit_code(expected):
    """In a forked child: 0 when a fresh robot's Jacobian is `expected`, 3 when it differs."""
    got = dqsym.Robot.from_file(PUMA).jacobian()
    os._exit(0 if got == expected else 3)


def run_forked(expected):
    """Forks a child that computes the Jacobian; its exit code, or a failure after LIMIT s."""
    ctx = multiprocessing.get_context("fork")
    p = ctx.Process(target=child_exit_code, args=(expected,))
    p.start()
    p.join(LIMIT)
    if p.is_alive():
        p.kill()
        p.join()
        pytest.fail(f"the forked child did not finish in {LIMIT} s (it waits on the parent's pool)")
    return p.exitcode


def test_a_child_forked_after_a_call_computes_the_same_jacobian():
    expected = dqsym.Robot.from_file(PUMA).jacobian()
    # Twice: the second child forks from a parent whose pool has served two calls.
    assert run_forked(expected) == 0
    assert dqsym.Robot.from_file(PUMA).jacobian() == expected
    assert run_forked(expected) == 0
    # The parent's own helpers still serve it after its children ended.
    assert dqsym.Robot.from_file(PUMA).jacobian() == expected


def test_children_forked_while_another_thread_computes_finish():
    expected = dqsym.Robot.from_file(PUMA).jacobian()
    stop = threading.Event()
    errors = []

    def busy():
        # Keeps the parent's pool in use (jobs queued and running, its lock taken and
        # released) while the main thread forks.
        try:
            while not stop.is_set():
                if dqsym.Robot.from_file(PUMA).jacobian() != expected:
                    errors.append("the parent's Jacobian changed")
        except BaseException as e:  # noqa: BLE001 - every failure is what the test reports
            errors.append(repr(e))

    t = threading.Thread(target=busy)
    t.start()
    try:
        codes = [run_forked(expected) for _ in range(6)]
    finally:
        stop.set()
        t.join()
    assert errors == []
    assert codes == [0] * 6
