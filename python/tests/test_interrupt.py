"""KeyboardInterrupt stops a long computation, the session survives it, and the GIL is
released while dqsym works."""

import os
import signal
import subprocess
import sys
import textwrap
import threading

import dqsym

CHILD = textwrap.dedent(
    """
    import sys
    import dqsym

    # Limits raised far enough that only an interrupt ends this in reasonable time: a sum of
    # 1,500 powers of sums, each about a tenth of a second of work.
    s = dqsym.Session(implicit_symbols=True, term_limit=10**7, work_budget=10**18)
    s.run("y = 2*a")
    huge = "x = " + " + ".join(f"(a{i} + b + c + d)^18" for i in range(1500))
    try:
        print("started", flush=True)
        s.run(huge)
        print("finished", flush=True)
    except KeyboardInterrupt as e:
        print("interrupted:", e, flush=True)
    # The session still works and kept its bindings.
    print("x bound:", "x" in s, flush=True)
    print("after:", s.eval("y + 1"), flush=True)
    """
)


def cpu_seconds(pid):
    """The user and system CPU time of process `pid` so far (Linux: /proc/PID/stat)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    # utime and stime are fields 14 and 15 of the line, 12 and 13 after the name.
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def test_sigint_stops_a_huge_expansion_and_the_session_still_works():
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        assert child.stdout.readline().strip() == "started"
        # Let the expansion get going: the child prints before it calls into dqsym, so a
        # fixed wait is a race on a busy machine (the interrupt then lands in the Python
        # lines before the call). Its CPU time tells instead: after "started" the child does
        # nothing but dqsym's work, so 0.3 s more of it means dqsym is well inside the sum.
        start = cpu_seconds(child.pid)
        while cpu_seconds(child.pid) < start + 0.3 and child.poll() is None:
            threading.Event().wait(0.01)
        child.send_signal(signal.SIGINT)
        # A guard against a hang only: the child stops in well under a second.
        out, err = child.communicate(timeout=120)
    finally:
        if child.poll() is None:
            child.kill()
    lines = out.splitlines()
    assert child.returncode == 0, err
    # The interruption came from inside dqsym (its message), not from the Python lines
    # around the call.
    assert lines[0].startswith("interrupted: dqsym: interrupted"), out
    assert lines[1] == "x bound: False"
    assert lines[2] == "after: 2*a + 1"


def test_the_gil_is_released_while_dqsym_works():
    # A statement that takes a while (a product of two 816-term sums: 666,000 term pairs,
    # about 0.4 s; a power of one sum alone is a multinomial expansion of milliseconds):
    # another Python thread runs meanwhile.
    s = dqsym.Session(implicit_symbols=True, term_limit=10**7, work_budget=10**12)
    started = threading.Event()
    done = threading.Event()
    terms = []

    def work():
        started.set()
        s.run("x = (a + b + c + d)^15 * (a - b + c - d)^15;")
        terms.append(1)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    ticks = 0
    while not done.is_set():
        ticks += 1
        done.wait(0.001)
    t.join()
    # Work is counted, not timed: with the GIL held, this thread could not have looped
    # while the statement ran; released, it loops many times.
    assert terms == [1]
    assert ticks > 20, ticks
