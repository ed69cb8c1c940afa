"""Bad print values: exit code 2, a one-line message, and no file (not even a temporary)."""

import pytest

from conftest import run_export

CASES = [
    (["--hinge-mm", "0.3"], "nozzle"),
    (["--hinge-mm", "0.5", "--nozzle-mm", "0.6"], "nozzle"),
    (["--hinge-mm", "25"], "does not fit"),
    (["--gap-mm", "-0.2"], "gap_mm"),
    (["--thickness-mm", "-2"], "thickness_mm"),
    (["--lamella-mm", "0"], "lamella_mm"),
    (["--nozzle-mm", "nan"], "nozzle_mm"),
    (["--lamella-mm", "3"], "thinner than"),
    (["--gap-mm", "30"], "gap_mm"),
]


@pytest.mark.parametrize("fmt", ["stl", "3mf"])
@pytest.mark.parametrize("flags,needle", CASES)
def test_bad_values_fail_in_one_line_and_leave_no_file(tmp_path, fmt, flags, needle):
    out = tmp_path / f"sheet.{fmt}"
    done = run_export("rotating-squares", fmt, out, *flags)
    assert done.returncode == 2, done.stderr
    message = done.stderr.strip()
    assert message and "\n" not in message, message
    assert needle in message, message
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []
