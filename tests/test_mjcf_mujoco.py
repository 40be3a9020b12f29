"""The MJCF reader against MuJoCo itself: poses, Jacobians, limits, inertials and joint couplings.

MuJoCo (PyPI ``mujoco``, in the ``compare`` extra) compiles the same files (``MjModel.from_xml_path``). At random
configurations (MuJoCo's ``qpos`` of the chain's joints, the other joints at ``qpos0``), after ``mj_kinematics`` and
``mj_comPos``:

* the site's (or body's) world pose ``site_xpos``/``site_xmat`` (``xpos``/``xmat``) is symjac's tool pose in {0},
  which is ``world``;
* ``[jacp; jacr]`` of ``mj_jacSite`` (``mj_jacBody``), world-frame rows [v; omega] at the site (the body's origin),
  restricted to the chain's degrees of freedom and multiplied by the coupling matrix C, is symjac's frame-{0}
  Jacobian at the end of the chain (the tool point, or the origin of {n} when the tip body ends in a joint);
* each chain link's mass, world centre of mass (``xipos``) and world tensor (``ximat diag(body_inertia) ximat^T``)
  is symjac's inertial of that link carried to {0} by ``T_0_i``;
* a joint equality holds (``efc_pos`` of its row is zero) when the follower is placed by symjac's coupling;
* random models (hypothesis: every orientation form, degrees or radians, any ``eulerseq``, hinge and slide joints
  with ``pos`` and ``ref``, several per body, sites placed by every form) agree the same way.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from symjac.kinematics.chain import forward_kinematics
from symjac.kinematics.coupling import coupling_matrix
from symjac.kinematics.numeric import numeric_at, numeric_jacobian
from symjac.model.io import load_robot

pytestmark = pytest.mark.external
mujoco = pytest.importorskip("mujoco", reason="MuJoCo is not installed (pip install mujoco, or the [compare] extra)")

DATA = Path(__file__).parent / "data" / "mjcf"
# (file, tip, whether the tip is a site)
CASES = {
    "frames": ("frames.xml", "tool", True),
    "frames at a body": ("frames.xml", "slider", False),
    "classes": ("classes.xml", "fingertip", True),
    "classes, site by class": ("classes.xml", "s3", True),
    "classes at a body": ("classes.xml", "b3", False),
    "classes, site from-to": ("classes.xml", "rod", True),
    "arm6": ("arm6/arm6.xml", "flange", True),
    "arm6 scene": ("arm6/scene.xml", "flange", True),
    "arm6 at its last body": ("arm6/arm6.xml", "wrist_3", False),
}
TOLERANCE = 1e-10


@pytest.fixture(autouse=True, scope="module")
def _scratch_folder(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """Run in a scratch folder: MuJoCo writes its warnings (a singular mass matrix of a random model) to
    ``MUJOCO_LOG.TXT`` in the working folder, which must not be the checkout."""
    previous = Path.cwd()
    os.chdir(tmp_path_factory.mktemp("mujoco"))
    yield
    os.chdir(previous)


def _load(case: str):
    name, tip, site = CASES[case]
    path = DATA / name
    robot = load_robot(path, tip_site=tip) if site else load_robot(path, tip_link=tip)
    model = mujoco.MjModel.from_xml_path(str(path))
    return robot, model, tip, site


def _joint(model, name: str):
    return model.joint(mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name))


def _configurations(robot, count: int = 5) -> list[np.ndarray]:
    rng = np.random.default_rng(43)
    return [rng.uniform(-1.2, 1.2, robot.n_coordinates) for _ in range(count)]


def _place(robot, model, data, q: np.ndarray) -> None:
    """MuJoCo's qpos for symjac's coordinates q: the chain's joints at theta(q), the others at qpos0."""
    data.qpos[:] = model.qpos0
    values = dict(zip(robot.q, q, strict=True))
    for joint, value in zip(robot.joints, robot.joint_values, strict=True):
        data.qpos[_joint(model, joint.name).qposadr[0]] = float(value.xreplace(values))
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)


@pytest.mark.parametrize("case", sorted(CASES))
def test_pose_and_jacobian_agree_with_mujoco(case):
    robot, model, tip, site = _load(case)
    data = mujoco.MjData(model)
    dofs = [_joint(model, joint.name).dofadr[0] for joint in robot.joints]
    C = np.array(coupling_matrix(robot).xreplace(robot.defaults), dtype=float)
    pose = forward_kinematics(robot, target="tool") if robot.tool is not None else forward_kinematics(robot)
    kind = mujoco.mjtObj.mjOBJ_SITE if site else mujoco.mjtObj.mjOBJ_BODY
    index = mujoco.mj_name2id(model, kind, tip)
    for q in _configurations(robot):
        _place(robot, model, data, q)
        jacp, jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
        if site:
            mujoco.mj_jacSite(model, data, jacp, jacr, index)
            position, rotation = data.site_xpos[index], data.site_xmat[index].reshape(3, 3)
        else:
            mujoco.mj_jacBody(model, data, jacp, jacr, index)
            position, rotation = data.xpos[index], data.xmat[index].reshape(3, 3)
        T = numeric_at(robot, pose, list(q))
        np.testing.assert_allclose(T[:3, 3], position, atol=TOLERANCE)
        np.testing.assert_allclose(T[:3, :3], rotation, atol=TOLERANCE)
        expected = np.vstack([jacp, jacr])[:, dofs] @ C
        np.testing.assert_allclose(numeric_jacobian(robot, q, 0), expected, atol=TOLERANCE)


@pytest.mark.parametrize("case", ["frames", "classes", "arm6 scene"])
def test_limits_and_kinds_agree_with_mujoco(case):
    robot, model, _, _ = _load(case)
    for joint in robot.joints:
        reference = _joint(model, joint.name)
        assert joint.type.value == {int(mujoco.mjtJoint.mjJNT_HINGE): "revolute",
                                    int(mujoco.mjtJoint.mjJNT_SLIDE): "prismatic"}[int(reference.type[0])]
        if reference.limited[0]:
            np.testing.assert_allclose(np.array(joint.limits, dtype=float), reference.range, atol=1e-15)
        else:
            assert joint.limits is None


@pytest.mark.parametrize("case", ["frames", "classes", "arm6"])
def test_inertials_agree_with_mujoco(case):
    robot, model, _, _ = _load(case)
    data = mujoco.MjData(model)
    # the body a joint moves last (several joints in one body: only the last carries the body)
    bodies = {}
    for joint in robot.joints:
        body = _joint(model, joint.name).bodyid[0]
        bodies = {key: value for key, value in bodies.items() if value != body}
        bodies[joint.index] = body
    for q in _configurations(robot, 3):
        _place(robot, model, data, q)
        for joint, inertial in zip(robot.joints, robot.inertials, strict=True):
            if joint.index not in bodies:
                assert inertial is None  # an intermediate link of a body with several joints
                continue
            body = bodies[joint.index]
            T = numeric_at(robot, forward_kinematics(robot, 0, joint.index), list(q))
            R, p = T[:3, :3], T[:3, 3]
            axes = data.ximat[body].reshape(3, 3)
            assert float(inertial.mass) == pytest.approx(model.body_mass[body], abs=1e-12)
            np.testing.assert_allclose(R @ np.array(inertial.com, dtype=float) + p, data.xipos[body], atol=1e-12)
            np.testing.assert_allclose(R @ np.array(inertial.inertia, dtype=float) @ R.T,
                                       axes @ np.diag(model.body_inertia[body]) @ axes.T, atol=1e-12)


def test_joint_equality_holds_where_the_coupling_places_the_follower():
    robot, model, _, _ = _load("classes")
    assert robot.coupling is not None and robot.n_coordinates == robot.n_joints - 1
    data = mujoco.MjData(model)
    equality = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_EQUALITY, "hand_coupling")
    for q in _configurations(robot):
        _place(robot, model, data, q)
        mujoco.mj_forward(model, data)
        rows = [i for i in range(data.nefc) if data.efc_type[i] == mujoco.mjtConstraint.mjCNSTR_EQUALITY
                and data.efc_id[i] == equality]
        assert len(rows) == 1
        assert abs(data.efc_pos[rows[0]]) < TOLERANCE
        # and it does not hold away from it: the test can fail
        data.qpos[_joint(model, "a5").qposadr[0]] += 0.1
        mujoco.mj_forward(model, data)
        assert abs(data.efc_pos[rows[0]]) > 0.05


def test_degrees_are_converted_where_mujoco_converts_them():
    robot, model, _, _ = _load("frames")  # degrees: hinge ranges and refs converted, slide ones not
    assert _joint(model, "j2").qpos0[0] == pytest.approx(np.radians(15), abs=1e-15)
    assert _joint(model, "d4").qpos0[0] == pytest.approx(0.05, abs=1e-15)
    assert robot.joints[3].limits == (0, pytest.approx(0.2))


# --- random models: every frame form, joint kind, offset and unit, against MuJoCo ---------------------------------

COORDINATE = st.sampled_from([0, 0, 0.1, -0.25, 0.4, 0.125])
VECTOR = st.lists(st.sampled_from([0, 1, -1, 0.5, 2, -0.3]), min_size=3, max_size=3).filter(lambda v: any(v))


@st.composite
def orientations(draw: st.DrawFn, degree: bool) -> str:
    angle = st.sampled_from([0, 30, -45, 90, 120, 17.5] if degree else [0, 0.5, -1.2, 1.5707963267948966, 2.5])
    kind = draw(st.sampled_from(["", "quat", "axisangle", "euler", "xyaxes", "zaxis"]))
    if kind == "quat":
        values = draw(st.lists(st.sampled_from([0, 1, -1, 0.5, 0.7071068, 2]), min_size=4, max_size=4)
                      .filter(lambda q: any(q)))
    elif kind == "axisangle":
        values = [*draw(VECTOR), draw(angle)]
    elif kind == "euler":
        values = [draw(angle) for _ in range(3)]
    elif kind == "xyaxes":
        x, y = draw(VECTOR), draw(VECTOR)
        assume(np.linalg.norm(np.cross(x, y)) > 0.1)
        values = [*x, *y]
    elif kind == "zaxis":
        values = draw(VECTOR)
    else:
        return ""
    return f' {kind}="{" ".join(str(v) for v in values)}"'


@st.composite
def models(draw: st.DrawFn) -> str:
    degree = draw(st.booleans())
    sequence = "".join(draw(st.lists(st.sampled_from("xyzXYZ"), min_size=3, max_size=3)))
    head = f'<compiler angle="{"degree" if degree else "radian"}" eulerseq="{sequence}"/>'
    bodies = draw(st.integers(1, 3))
    text = ""
    for index in range(bodies):
        pos = " ".join(str(draw(COORDINATE)) for _ in range(3))
        text += f'<body name="b{index}" pos="{pos}"{draw(orientations(degree))}>'
        text += '<inertial pos="0.01 0 0.02" mass="1" diaginertia="0.01 0.02 0.03"/>'
        for number in range(draw(st.integers(1 if index == 0 else 0, 2))):
            kind = draw(st.sampled_from(["hinge", "hinge", "slide"]))
            ref = draw(st.sampled_from([0, 0, 0.2, -0.5] if kind == "slide" or not degree else [0, 0, 20, -35]))
            pos = " ".join(str(draw(COORDINATE)) for _ in range(3))
            axis = " ".join(str(v) for v in draw(VECTOR))
            text += f'<joint name="j{index}_{number}" type="{kind}" axis="{axis}" pos="{pos}" ref="{ref}"/>'
    pos = " ".join(str(draw(COORDINATE)) for _ in range(3))
    text += f'<site name="end" pos="{pos}"{draw(orientations(degree))}/>' + "</body>" * bodies
    return f'<mujoco model="random">{head}<worldbody>{text}</worldbody></mujoco>'


@settings(max_examples=12, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
@given(models())
def test_random_models_agree_with_mujoco(tmp_path_factory, text):
    path = tmp_path_factory.mktemp("random") / "random.xml"
    path.write_text(text, encoding="utf-8")
    robot = load_robot(path, tip_site="end")
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    dofs = [_joint(model, joint.name).dofadr[0] for joint in robot.joints]
    pose = forward_kinematics(robot, target="tool")
    for q in _configurations(robot, 2):
        _place(robot, model, data, q)
        jacp, jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
        mujoco.mj_jacSite(model, data, jacp, jacr, 0)
        T = numeric_at(robot, pose, list(q))
        np.testing.assert_allclose(T[:3, 3], data.site_xpos[0], atol=TOLERANCE, err_msg=text)
        np.testing.assert_allclose(T[:3, :3], data.site_xmat[0].reshape(3, 3), atol=TOLERANCE, err_msg=text)
        np.testing.assert_allclose(numeric_jacobian(robot, q, 0), np.vstack([jacp, jacr])[:, dofs], atol=TOLERANCE,
                                   err_msg=text)
