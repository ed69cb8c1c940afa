"""Deployment: every method and setting, the report equal to `isogami deploy --json` to 1e-12,
per-frame numpy arrays consistent with it and with each other, bad inputs refused."""

import math

import numpy as np
import pytest

import isogami
from conftest import assert_same

CASES = [
    ("rotating-squares", []),
    ("rotating-squares", ["--method", "ncm"]),
    ("rotating-squares", ["--method", "springs"]),
    ("rotating-squares", ["--kerf", "0.03", "--frame-count", "12"]),
    ("rotating-squares", ["--all-steps"]),
    (isogami.SAMPLE_OPENING_DESIGNS[1], []),
    (isogami.SAMPLE_OPENING_DESIGNS[3], ["--method", "ncm", "--kerf", "0.02"]),
    (isogami.COMPARISON_DESIGNS[0], ["--method", "springs"]),
    ("IH76::2x2:bbbb----", ["--mode", "1"]),
]


def python_args(flags):
    """The keyword arguments of `deploy` for CLI flags."""
    kw, i = {}, 0
    while i < len(flags):
        f = flags[i]
        if f == "--all-steps":
            kw["frames"] = "all"
            i += 1
            continue
        v = flags[i + 1]
        i += 2
        if f == "--method":
            kw["method"] = v
        elif f == "--kerf":
            kw["kerf"] = float(v)
        elif f == "--frame-count":
            kw["frames"] = int(v)
        elif f == "--mode":
            kw["mode"] = int(v)
    return kw


@pytest.mark.parametrize("spec,flags", CASES)
def test_report_and_arrays_equal_the_cli(cli, spec, flags):
    want = cli("deploy", "--design", spec, "--json", *flags)
    run = isogami.deploy(spec, **python_args(flags))
    assert isinstance(run, isogami.Deployment)
    assert_same(run.report(), want)
    frames = want["frames"]
    n, tiles = len(frames), len(frames[0]["tiles"])
    assert len(run) == n
    close = lambda got, w: np.allclose(got, w, rtol=1e-12, atol=1e-12)  # noqa: E731
    assert close(run.t, [f["t"] for f in frames])
    assert run.step.tolist() == [f["step"] for f in frames]
    assert run.F.shape == (n, 2, 2) and close(run.F, [f["F"] for f in frames])
    assert run.U.shape == (n, 2, 2) and close(run.U, [f["measures"]["u"] for f in frames])
    pe = [[f["measures"]["min_expansion"], f["measures"]["max_expansion"]] for f in frames]
    assert run.principal_expansions.shape == (n, 2) and close(run.principal_expansions, pe)
    assert close(run.area_ratio, [f["measures"]["area_ratio"] for f in frames])
    assert close(run.principal_angle, [f["measures"]["principal_angle"] for f in frames])
    assert close(run.lattice_rotation, [f["measures"]["lattice_rotation"] for f in frames])
    assert run.tile_rotations.shape == (n, tiles)
    assert close(run.tile_rotations, [f["measures"]["tile_rotations"] for f in frames])
    poses = [[[p["x"], p["y"], p["theta"]] for p in f["tiles"]] for f in frames]
    assert run.tile_poses.shape == (n, tiles, 3) and close(run.tile_poses, poses)
    assert close(run.tiling_vectors, [[f["u"], f["w"]] for f in frames])
    assert close(run.joint_residual, [f["joint_residual"] for f in frames])
    assert close(run.clearance, [f["min_clearance"] for f in frames])
    for name in ["design", "method", "kerf", "length_scale", "dof", "steps", "attempts", "arc_length",
                 "max_joint_residual", "min_clearance", "behaviour", "max_expansion", "min_expansion",
                 "max_area_ratio", "max_tile_rotation"]:
        assert_same(getattr(run, name), want[name], name)
    assert run.end_reason == want["end_reason"]["kind"]


def test_rotating_squares_open_to_area_two():
    run = isogami.deploy("rotating-squares")
    # Squares turn by 45° at the widest: area ratio (cos 45° + sin 45°)² = 2.
    assert f"{run.area_ratio.max():.4g}" == "2"
    assert run.behaviour == "isotropic_auxetic" and run.end_reason == "contact_limit"
    assert run.max_area_ratio == run.area_ratio.max()


def test_arrays_agree_with_each_other():
    run = isogami.deploy(isogami.SAMPLE_OPENING_DESIGNS[2], frames=25)
    t = run.t
    assert t[0] == 0 and t[-1] == 1 and np.all(np.diff(t) > 0)
    assert np.allclose(run.area_ratio, np.linalg.det(run.F), rtol=1e-12, atol=1e-12)
    U = run.U
    assert np.allclose(U, np.transpose(U, (0, 2, 1)), atol=1e-14)
    # F = R U with R a rotation by the lattice rotation.
    c, s = np.cos(run.lattice_rotation), np.sin(run.lattice_rotation)
    R = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)
    assert np.allclose(R @ U, run.F, atol=1e-12)
    eig = np.linalg.eigvalsh(U) - 1
    assert np.allclose(eig, run.principal_expansions, atol=1e-12)
    # [u w] = F [u0 w0].
    closed = run.tiling_vectors[0].T
    assert np.allclose(run.F @ closed, np.transpose(run.tiling_vectors, (0, 2, 1)), atol=1e-9)
    assert np.all(run.joint_residual <= 1e-8) and np.all(run.clearance > 0)
    assert run.states.shape[0] == len(run)
    assert np.allclose(run.states[:, :3], run.states[0, :3])  # tile 0 is held fixed
    assert np.isfinite(run.states).all()


def test_profile_and_frame_selection():
    run = isogami.deploy(isogami.SAMPLE_OPENING_DESIGNS[1])
    k = run.frame_index(0.5)
    assert abs(run.t[k] - 0.5) == np.min(np.abs(run.t - 0.5))
    p = run.profile(t=0.5, samples=90)
    assert p.shape == (90, 2)
    theta, eps = p[:, 0], p[:, 1]
    d = np.stack([np.cos(theta), np.sin(theta)], 1)
    U = run.U[k]
    assert np.allclose(eps, np.einsum("ij,jk,ik->i", d, U - np.eye(2), d), atol=1e-12)
    lo, hi = run.principal_expansions[k]
    assert lo - 1e-9 <= eps.min() and eps.max() <= hi + 1e-9
    assert np.array_equal(run.profile(frame=-1), run.profile(frame=len(run) - 1))
    assert np.array_equal(run.profile(), run.profile(frame=len(run) - 1))
    with pytest.raises(IndexError):
        run.profile(frame=len(run))
    with pytest.raises(TypeError):
        run.profile(t=0.5, frame=0)
    with pytest.raises(isogami.SettingsError):
        run.profile(samples=2)
    with pytest.raises(ValueError):
        run.frame_index(float("nan"))


def test_classify_with_other_tolerances():
    run = isogami.deploy(isogami.COMPARISON_DESIGNS[0])
    assert run.classify() == run.behaviour == "orthotropic_positive_poisson"
    # Thresholds wide enough to call its contraction negligible; a floor above its expansion.
    assert run.classify(orthotropic=10.0) == "anisotropic_auxetic"
    assert run.classify(absolute=10.0) is None
    squares = isogami.deploy("rotating-squares")
    assert squares.classify() == "isotropic_auxetic"
    assert squares.classify(isotropic=-1.0) == "anisotropic_auxetic"
    with pytest.raises(ValueError):
        squares.classify(isotropic=float("nan"))


def test_frame_svgs_and_json():
    run = isogami.deploy("rotating-squares", frames=5)
    svgs = run.frame_svgs(width=200)
    assert len(svgs) == len(run) and all("<svg" in s and s.rstrip().endswith("</svg>") for s in svgs)
    assert "t = 1.00" in svgs[-1]
    import json

    assert json.loads(run.to_json()) == run.report()
    assert "Deployment" in repr(run) and "<svg" in run._repr_svg_()


def test_settings_object_and_overrides():
    s = isogami.DeploySettings()
    for name in isogami.DEPLOY_SETTINGS:
        assert name in s.to_dict()
    assert s.method == "rigid-modes" and s.kerf == 0.01 and s.dhat == 0.005 and s.mode is None
    k = isogami.DeploySettings(kerf=0.04)
    assert k.dhat == 0.02 and k.stiffness == s.stiffness
    assert isogami.DeploySettings(kerf=0.04, dhat=0.01).dhat == 0.01
    assert isogami.DeploySettings(dhat=0.01, kerf=0.04).dhat == 0.01  # order does not matter
    r = s.replace(method="ncm", max_steps=7)
    assert (r.method, r.max_steps, s.max_steps) == ("ncm", 7, 5000)
    assert r == isogami.DeploySettings(method="ncm", max_steps=7) and r != s
    assert "max_steps=7" in repr(r)
    by_object = isogami.deploy("rotating-squares", s.replace(kerf=0.02), frames=10)
    by_keyword = isogami.deploy("rotating-squares", kerf=0.02, frames=10)
    assert by_object.report() == by_keyword.report()
    limited = isogami.deploy("rotating-squares", r)
    # 7 accepted steps: 8 states with the closed one.
    assert limited.method == "ncm" and limited.steps == 8 and limited.end_reason == "max_steps"
    # A keyword overrides the settings object.
    assert isogami.deploy("rotating-squares", r, method="rigid-modes").method == "rigid-modes"


@pytest.mark.parametrize(
    "kwargs,error,needle",
    [
        (dict(kerf=float("nan")), isogami.SettingsError, "kerf NaN"),
        (dict(kerf=0.5), isogami.SettingsError, "kerf 0.5"),
        (dict(dhat=0.02), isogami.SettingsError, "dhat"),
        (dict(method="bogus"), isogami.SettingsError, "method 'bogus'"),
        (dict(step_weight=-1.0), isogami.SettingsError, "step_weight"),
        (dict(growth=0.5), isogami.SettingsError, "growth"),
        (dict(max_halvings=99), isogami.SettingsError, "max_halvings"),
        (dict(max_steps=0), isogami.SettingsError, "max_steps"),
        (dict(max_stretch=float("inf")), isogami.SettingsError, "max_stretch"),
        (dict(mobility_tol=2.0), isogami.SettingsError, "mobility tolerance"),
        (dict(frame_joint_tolerance=1e-12), isogami.SettingsError, "frame_joint_tolerance"),
        (dict(mode=3), isogami.SettingsError, "mode 3"),
        (dict(frames=1), isogami.SettingsError, "frame count 1"),
        (dict(frames=-5), isogami.SettingsError, "frame count"),
        (dict(frames=10**6), isogami.SettingsError, "frame count"),
        (dict(frames="some"), TypeError, "frames"),
        (dict(frames=True), TypeError, "frames"),
        (dict(frames=2.5), TypeError, "frames"),
        (dict(kerf="wide"), TypeError, "kerf"),
        (dict(max_steps=-1), TypeError, "max_steps"),
        (dict(max_steps=1.5), TypeError, "max_steps"),
        (dict(method=3), TypeError, "method"),
        (dict(colour="red"), TypeError, "unexpected setting 'colour'"),
        (dict(settings="fast"), TypeError, "DeploySettings"),
        (dict(timeout=-1.0), isogami.SettingsError, "timeout"),
        (dict(timeout=float("nan")), isogami.SettingsError, "timeout"),
        (dict(progress=42), TypeError, "progress must be callable"),
    ],
)
def test_bad_settings_are_refused_before_running(kwargs, error, needle):
    with pytest.raises(error, match=needle):
        isogami.deploy("rotating-squares", **kwargs)


def test_settings_validate_names_the_setting():
    isogami.DeploySettings().validate()
    with pytest.raises(isogami.SettingsError, match="initial_step"):
        isogami.DeploySettings(initial_step=0.0).validate()
    with pytest.raises(TypeError, match="unexpected setting"):
        isogami.DeploySettings(kerff=0.1)


def test_designs_that_do_not_deploy():
    with pytest.raises(isogami.DeployError, match="rigid"):
        isogami.deploy("IH90::1x1:xxx")
    with pytest.raises(isogami.DesignError):
        isogami.deploy("IH90::1x1:x")
    with pytest.raises(isogami.TilingError):
        isogami.deploy("IH1000::1x1:x")
    with pytest.raises(TypeError, match="design must be"):
        isogami.deploy(["rotating-squares"])
    with pytest.raises(TypeError):
        isogami.deploy()


def test_design_object_and_text_give_the_same_deployment():
    d = isogami.design(isogami.SAMPLE_OPENING_DESIGNS[4])
    assert isogami.deploy(d).report() == isogami.deploy(d.spec).report() == isogami.deploy(d.to_json()).report()


def test_all_steps_hold_every_accepted_state():
    run = isogami.deploy("rotating-squares", frames="all")
    assert len(run) == run.steps and run.step.tolist() == list(range(run.steps))
    assert math.isclose(run.t[-1], 1.0)
