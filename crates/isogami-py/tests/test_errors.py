"""Exceptions: one class per kind of library error, below IsogamiError, with the library's
message; the kind is the stage that failed, however deeply the library wrapped it."""

import pytest

import isogami

KINDS = [
    isogami.TilingError,
    isogami.CellError,
    isogami.DesignError,
    isogami.KinematicsError,
    isogami.MobilityError,
    isogami.ContactError,
    isogami.DeployError,
    isogami.CancelledError,
    isogami.MeasureError,
    isogami.LinkageError,
    isogami.ExploreError,
    isogami.SettingsError,
    isogami.StoreError,
    isogami.QueryError,
    isogami.ExportError,
]


def test_every_kind_is_an_isogami_error():
    assert issubclass(isogami.IsogamiError, Exception)
    assert len(set(KINDS)) == len(KINDS)
    for kind in KINDS:
        assert issubclass(kind, isogami.IsogamiError) and kind.__module__ == "isogami"
        assert kind.__doc__
    assert issubclass(isogami.CancelledError, isogami.DeployError)
    assert issubclass(isogami.QueryError, isogami.StoreError)


def test_kind_follows_the_failing_stage_through_wrapping(cli_raw):
    # Inside a spec string the library wraps tiling and cell errors in its design error.
    cases = [
        ("IH999::1x1:a", isogami.TilingError),
        ("IH76::7x1:a", isogami.CellError),
        ("IH76::1x1:a", isogami.DesignError),
    ]
    for spec, kind in cases:
        with pytest.raises(kind) as caught:
            isogami.design(spec)
        done = cli_raw("analyze", "--design", spec)
        # The same one-line message as the command line prints.
        assert done.stderr.decode().strip() == f"error: {caught.value}"
        assert type(caught.value) is kind


def test_contact_errors_come_from_the_contact_model():
    # A tile with a very short edge: inset by half of the widest kerf, the edge vanishes.
    spec = "IH1:-0.3521566340865392,0.5414124727934966,0.5825446417955106,0.47650529711026557:1x1:---"
    isogami.design(spec)  # a valid tiling
    with pytest.raises(isogami.ContactError, match="collision polygon inset by kerf/2"):
        isogami.deploy(spec, kerf=0.2)
    # The deploy settings error of a comparison is a SettingsError, not a DeployError.
    with pytest.raises(isogami.SettingsError):
        isogami.compare(spec, kerf=1.0)
