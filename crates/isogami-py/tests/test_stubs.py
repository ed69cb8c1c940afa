"""The type stubs match the built module (issue 23 item 17): mypy's stubtest reports no
error (classes final as at runtime, `__new__` where the runtime has it, read-only record
fields, every name in the stubs present at runtime). scripts/test-python installs mypy."""

import subprocess
import sys


def test_stubtest_is_clean():
    done = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "isogami"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]
    assert "Success" in done.stdout, done.stdout
