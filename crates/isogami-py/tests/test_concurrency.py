"""Long calls: progress callbacks, cancellation, timeouts, the GIL released while the library
runs (other Python threads go on; deployments in threads give the serial results), Ctrl-C."""

import os
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import pytest

import isogami

# Rotating squares with tiny steps: a deployment that runs for minutes unless stopped.
ENDLESS = dict(initial_step=1e-6, max_step=1e-6, max_steps=10**8, max_attempts=10**8)
# About half a second or more of work in one call.
LONG = dict(initial_step=2e-4, max_step=2e-4, max_steps=20000, max_attempts=40000)


def test_progress_reports_every_accepted_step():
    calls = []
    run = isogami.deploy("rotating-squares", progress=calls.append)
    assert len(calls) >= run.steps - 1
    assert calls[-1] == run.steps and calls[0] >= 2
    # Once it is past the probe of the opening sign, the count grows by one per step.
    tail = calls[-(run.steps - 5):]
    assert all(b == a + 1 for a, b in zip(tail, tail[1:]))


def test_progress_returning_false_cancels():
    calls = []

    def stop_at_five(n):
        calls.append(n)
        return n < 5

    with pytest.raises(isogami.CancelledError, match="progress callback returned False"):
        isogami.deploy("rotating-squares", progress=stop_at_five)
    assert calls[-1] == 5
    assert issubclass(isogami.CancelledError, isogami.DeployError)


def test_progress_exception_is_raised_from_deploy():
    class Stop(Exception):
        pass

    def boom(n):
        raise Stop(f"at {n}")

    with pytest.raises(Stop, match="at 2"):
        isogami.deploy("rotating-squares", progress=boom)


def test_progress_returning_none_goes_on():
    run = isogami.deploy("rotating-squares", progress=lambda n: None)
    assert run.end_reason == "contact_limit"


def test_timeout_stops_a_long_run():
    started = time.perf_counter()
    with pytest.raises(isogami.CancelledError, match="timeout of 0.2 s"):
        isogami.deploy("rotating-squares", timeout=0.2, **ENDLESS)
    assert time.perf_counter() - started < 60  # the run would take minutes


def test_compare_and_export_take_progress_and_cancel():
    seen = []
    c = isogami.compare("rotating-squares", progress=seen.append)
    assert len(c) == 3 and len(seen) >= sum(r.steps - 1 for r in c.results)
    with pytest.raises(isogami.CancelledError):
        isogami.compare("rotating-squares", progress=lambda n: n < 3)
    with pytest.raises(isogami.CancelledError):
        isogami.export("rotating-squares", "obj", progress=lambda n: False)
    with pytest.raises(isogami.CancelledError, match="timeout"):
        isogami.compare("rotating-squares", timeout=0.05, **ENDLESS)


def test_deploy_releases_the_gil():
    """While a deployment runs in one thread, another Python thread keeps running. With the
    GIL held for the whole call no tick could land inside its middle 80 %."""
    window = {}

    def work():
        window["start"] = time.perf_counter()
        isogami.deploy("rotating-squares", **LONG)
        window["end"] = time.perf_counter()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    start, end = window["start"], window["end"]
    span = end - start
    assert span > 0.05, f"the deployment took only {span:.3f} s: too short to tell"
    inside = [t for t in ticks if start + 0.1 * span < t < end - 0.1 * span]
    assert len(inside) > 10, f"{len(inside)} ticks of the other thread during a {span:.3f} s call"


def test_deployments_in_threads_equal_serial_ones():
    specs = list(isogami.SAMPLE_OPENING_DESIGNS[:4])
    serial = [isogami.deploy(s).report() for s in specs]
    with ThreadPoolExecutor(max_workers=2) as pool:
        parallel = list(pool.map(lambda s: isogami.deploy(s).report(), specs))
    assert parallel == serial


CTRL_C = """
import signal, sys, time
signal.signal(signal.SIGINT, signal.default_int_handler)
import isogami
print("ready", flush=True)
try:
    isogami.deploy("rotating-squares", initial_step=1e-6, max_step=1e-6, max_steps=10**8, max_attempts=10**8)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


@pytest.mark.skipif(os.name != "posix", reason="sends SIGINT")
def test_ctrl_c_interrupts_a_deployment():
    child = subprocess.Popen(
        [sys.executable, "-c", CTRL_C], stdout=subprocess.PIPE, text=True
    )
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(0.5)
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=120)
    finally:
        if child.poll() is None:
            child.kill()
    assert out.strip() == "interrupted"
    assert child.returncode == 0
