#!/usr/bin/env python3
"""Pinocchio's values for robots/tests/pinocchio.rs, printed as TOML on stdout.

For each case (a URDF of the `example-robot-data` package, a base link, a tip link and a tool
offset in the tip frame) and each of a few seeded random states (theta, thetadot) of the joints
on the path from the base to the tip, the script prints:

- the world placement of the base link (the Rust chain takes it as its base transform),
- the tool point and the tool frame's rotation (world),
- the 6 x n Jacobian of the tool frame in LOCAL_WORLD_ALIGNED (linear rows, then angular) and
  its time derivative along thetadot (getFrameJacobianTimeVariation),
- H (crba, symmetrised), c = nonLinearEffects - g and g = computeGeneralizedGravity,

restricted to the path's joints. Every joint off the path (a gripper's fingers, say) has its
inertia set to zero, since a chain from base to tip leaves such branches out, and stays at its
neutral position. Floats are printed with repr (shortest round trip), so the Rust side reads
the same doubles. Needs `pin` and `example-robot-data` (PyPI).
"""

import importlib.metadata
import math
import sys

import numpy as np
import pinocchio as pin

SAMPLES = 20
SEED = 38

CASES = [
    # name, URDF under the package's robots/, base link, tip link, tool offset (m, tip frame)
    ("ur5", "ur_description/urdf/ur5_robot.urdf", "base_link", "tool0", (0.01, -0.02, 0.15)),
    ("panda", "panda_description/urdf/panda.urdf", "panda_link0", "panda_hand_tcp", (0.0, 0.0, 0.0)),
    # Seven revolute joints and the prismatic left finger; the right finger is a branch.
    ("panda-finger", "panda_description/urdf/panda.urdf", "panda_link0", "panda_leftfinger", (0.0, 0.01, 0.05)),
    ("kinova", "kinova_description/robots/kinova.urdf", "j2s6s200_link_base", "j2s6s200_end_effector", (0.0, 0.0, 0.1)),
    ("z1", "z1_description/urdf/z1.urdf", "link00", "link06", (0.05, 0.0, 0.0)),
    ("xarm7", "xarm_description/urdf/xarm7.urdf", "link_base", "link_eef", (0.0, 0.0, 0.05)),
]


def robots_dir():
    dist = importlib.metadata.distribution("example-robot-data")
    return dist.locate_file("cmeel.prefix/share/example-robot-data/robots")


def toml_value(x):
    if isinstance(x, str):
        return '"' + x.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(x, (list, tuple, np.ndarray)):
        return "[" + ", ".join(toml_value(v) for v in x) + "]"
    return repr(float(x))


def path_joints(model, base, tip):
    """The joints from the base link's joint (exclusive) down to the tip link's joint."""
    base_joint = model.frames[model.getFrameId(base)].parentJoint
    tip_joint = model.frames[model.getFrameId(tip)].parentJoint
    support = list(model.supports[tip_joint])
    if base_joint not in support:
        sys.exit(f"{tip} is not below {base}")
    return support[support.index(base_joint) + 1:]


def random_angle(rng, joint_model, lower, upper):
    if math.isfinite(lower) and math.isfinite(upper) and upper > lower and upper - lower < 20:
        return rng.uniform(lower, upper)
    return rng.uniform(-math.pi, math.pi)


def case(out, rng, root, name, urdf, base, tip, tool):
    path = str(root / urdf)
    model = pin.buildModelFromUrdf(path)
    joints = path_joints(model, base, tip)
    for j in range(1, model.njoints):
        if j not in joints:
            model.inertias[j] = pin.Inertia.Zero()
    tip_id = model.getFrameId(tip)
    tip_frame = model.frames[tip_id]
    tool_placement = tip_frame.placement * pin.SE3(np.eye(3), np.array(tool, dtype=float))
    tool_id = model.addFrame(
        pin.Frame("driftbench_tool", tip_frame.parentJoint, tip_id, tool_placement, pin.FrameType.OP_FRAME)
    )
    data = model.createData()
    v_idx = [model.joints[j].idx_v for j in joints]
    out.append("[[case]]")
    for key, value in [("name", name), ("urdf", path), ("base", base), ("tip", tip), ("tool", tool)]:
        out.append(f"{key} = {toml_value(value)}")
    out.append(f"joints = {toml_value([model.names[j] for j in joints])}")
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    base_pose = data.oMf[model.getFrameId(base)]
    out.append(f"base_rotation = {toml_value([list(r) for r in base_pose.rotation])}")
    out.append(f"base_translation = {toml_value(base_pose.translation)}")
    for _ in range(SAMPLES):
        q = pin.neutral(model)
        v = np.zeros(model.nv)
        theta, thetadot = [], []
        for j in joints:
            jm = model.joints[j]
            lo, hi = model.lowerPositionLimit[jm.idx_q], model.upperPositionLimit[jm.idx_q]
            if jm.nq == 2:  # a continuous joint: (cos, sin)
                t = rng.uniform(-math.pi, math.pi)
                q[jm.idx_q : jm.idx_q + 2] = (math.cos(t), math.sin(t))
            else:
                t = random_angle(rng, jm, lo, hi)
                q[jm.idx_q] = t
            td = rng.uniform(-1.0, 1.0)
            v[jm.idx_v] = td
            theta.append(t)
            thetadot.append(td)
        pin.framesForwardKinematics(model, data, q)
        tool_pose = data.oMf[tool_id]
        jac = pin.computeFrameJacobian(model, data, q, tool_id, pin.LOCAL_WORLD_ALIGNED)[:, v_idx]
        pin.computeJointJacobiansTimeVariation(model, data, q, v)
        pin.updateFramePlacements(model, data)
        jac_dot = pin.getFrameJacobianTimeVariation(model, data, tool_id, pin.LOCAL_WORLD_ALIGNED)[:, v_idx]
        mass = pin.crba(model, data, q)
        mass = np.triu(mass) + np.triu(mass, 1).T
        g = pin.computeGeneralizedGravity(model, data, q).copy()
        c = pin.nonLinearEffects(model, data, q, v) - g
        out.append("[[case.sample]]")
        out.append(f"theta = {toml_value(theta)}")
        out.append(f"thetadot = {toml_value(thetadot)}")
        out.append(f"position = {toml_value(tool_pose.translation)}")
        out.append(f"rotation = {toml_value([list(r) for r in tool_pose.rotation])}")
        out.append(f"jacobian = {toml_value([list(r) for r in jac])}")
        out.append(f"jacobian_dot = {toml_value([list(r) for r in jac_dot])}")
        out.append(f"inertia = {toml_value([list(mass[i, v_idx]) for i in v_idx])}")
        out.append(f"coriolis = {toml_value(c[v_idx])}")
        out.append(f"gravity = {toml_value(g[v_idx])}")


def main():
    rng = np.random.default_rng(SEED)
    root = robots_dir()
    out = [
        f"pinocchio = {toml_value(pin.__version__)}",
        f"example_robot_data = {toml_value(importlib.metadata.version('example-robot-data'))}",
    ]
    for c in CASES:
        case(out, rng, root, *c)
    print("\n".join(out))


if __name__ == "__main__":
    main()
