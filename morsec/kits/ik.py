"""Inverse kinematics for a component's own joints (an arm): MuJoCo's Jacobians, damped least squares.

    ik = InverseKinematics(sim.model, servos)           # servos: a morsec.kits.servos.JointServos
    q, dist, angle = ik.solve(sim.data, body, pos, rot, tolerances=(0.005, 0.01), restarts=8)

`solve` puts the origin of `body` (a link of the arm) at `pos` (and its frame at `rot`), world frame: damped
least squares on `mj_jacBody` of that body, on a scratch MjData (the simulation's own is never touched),
the joints held within their limits. It returns joint values (root to tip, as `servos.names`) and how far
from the target they leave the body. A target out of reach gives the least-squares compromise between
position and orientation, an angle error counting `rot_weight` metres per radian."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from morsec.kits.geometry import matrix_to_quat, quat_to_matrix

IK_DAMPING = 0.02  # damped least squares: lambda, m (rad)
IK_MAX_STEP = 0.2  # rad (m) per iteration and joint
IK_BETTER = 1e-6  # m^2: how much lower a restart's squared error must be to replace the first try's
IK_MAX_DAMPING = 100.0  # Levenberg-Marquardt: no step lowers the error even this damped: a minimum


class InverseKinematics:
    """Inverse kinematics of the joints of `servos` (a JointServos, or anything with its `qpos`, `dof`,
    `limited`, `range` and `clamp`) in `model`."""

    def __init__(self, model, servos):
        self.model = model
        self.servos = servos
        self.scratch = mujoco.MjData(model)

    def solve(self, data, body: int, pos, rot=None, *, tolerances: tuple[float, float], start=None,
              iterations: int = 200, restarts: int = 0, rot_weight: float = 1.0) -> tuple[np.ndarray, float, float]:
        """Joint values (within the limits) putting body `body`'s origin at `pos` (and its frame at `rot`),
        from `start` (default: the joints in `data`, the simulation's MjData, which also gives the rest of
        the model: the robot's pose, other joints): damped least squares on MuJoCo's Jacobian, joints at a
        limit that the step would push further left out of the step. If that does not reach the target
        within half the `tolerances` (m, rad), up to `restarts` more tries from the zero pose and from fixed
        pseudo-random poses (deterministic). Out of reach, the joints settle where the sum of the squared
        distance and the squared angle times `rot_weight` (m/rad) is least. Returns (joints, remaining
        distance m, remaining angle rad) of the best try."""
        servos = self.servos
        tol_p, tol_a = tolerances
        best = None
        seeds = np.random.default_rng(0)
        first = np.array(data.qpos[servos.qpos] if start is None else start, dtype=float)
        for attempt in range(restarts + 1):
            if attempt == 0:
                q0 = first
            elif attempt == 1:
                q0 = servos.clamp(np.zeros_like(first))
            else:
                lo = np.where(servos.limited, servos.range[:, 0], -math.pi)
                hi = np.where(servos.limited, servos.range[:, 1], math.pi)
                q0 = lo + seeds.random(len(first)) * (hi - lo)
            q, err_p, err_a = self._dls(data, body, pos, rot, q0, iterations, tol_p, tol_a, rot_weight)
            score = err_p ** 2 + (rot_weight * err_a) ** 2
            # another start must do clearly better: out of reach, the same compromise is found from many
            # starts, in other (twisted) poses of a redundant arm; the first, from where the arm is, is kept
            if best is None or score < best[0] - IK_BETTER:
                best = (score, q, err_p, err_a)
            if err_p <= tol_p / 2 and err_a <= tol_a / 2:
                break
        return best[1], best[2], best[3]

    def _dls(self, data, body: int, pos, rot, q, iterations: int, tol_p: float, tol_a: float,
             rot_weight: float) -> tuple[np.ndarray, float, float]:
        """Levenberg-Marquardt: damped least-squares steps, a step that does not lower the (weighted) error
        retried with more damping. So an unreachable target's iterations settle on the least error instead
        of swinging about it (a stretched arm is singular: the Jacobian does not see that bending loses
        reach)."""
        m, d, servos = self.model, self.scratch, self.servos
        d.qpos[:] = data.qpos
        q = servos.clamp(q)
        cols = servos.dof
        jacp, jacr = np.zeros((3, m.nv)), np.zeros((3, m.nv))
        lo = np.where(servos.limited, servos.range[:, 0], -np.inf)
        hi = np.where(servos.limited, servos.range[:, 1], np.inf)
        pos = np.asarray(pos, dtype=float)
        rot = None if rot is None else np.asarray(rot)

        def evaluate(q):
            d.qpos[servos.qpos] = q
            mujoco.mj_kinematics(m, d)
            mujoco.mj_comPos(m, d)
            ep = pos - d.xpos[body]
            if rot is None:
                return ep, float(np.linalg.norm(ep)), 0.0
            er = rotation_error(rot, d.xmat[body].reshape(3, 3))
            return np.concatenate([ep, rot_weight * er]), float(np.linalg.norm(ep)), float(np.linalg.norm(er))

        err, err_p, err_a = evaluate(q)
        damping = IK_DAMPING
        for _ in range(iterations):
            if err_p < tol_p / 20 and err_a < tol_a / 20:
                break
            mujoco.mj_jacBody(m, d, jacp, jacr, body)
            jac = jacp[:, cols] if rot is None else np.vstack([jacp[:, cols], rot_weight * jacr[:, cols]])
            free = np.ones(len(q), dtype=bool)
            for _ in range(len(q)):  # joints stuck at a limit leave the step
                j = jac * free
                dq = j.T @ np.linalg.solve(j @ j.T + damping ** 2 * np.eye(len(err)), err)
                stuck = free & (((q <= lo + 1e-9) & (dq < 0)) | ((q >= hi - 1e-9) & (dq > 0)))
                if not stuck.any():
                    break
                free &= ~stuck
            biggest = float(np.max(np.abs(dq))) if len(dq) else 0.0
            if biggest > IK_MAX_STEP:
                dq *= IK_MAX_STEP / biggest
            trial = servos.clamp(q + dq)
            new = evaluate(trial)
            if new[0] @ new[0] < err @ err:
                q, (err, err_p, err_a) = trial, new
                damping = max(IK_DAMPING, damping / 2)
            else:
                damping *= 4
                if damping > IK_MAX_DAMPING:
                    break  # no step lowers the error: as near as it gets
                evaluate(q)  # back to q's kinematics for the next Jacobian
        return q, err_p, err_a


def rotation_error(target: np.ndarray, current: np.ndarray) -> np.ndarray:
    """Rotation vector (world frame, rad) turning `current` into `target`."""
    quat = matrix_to_quat(np.asarray(target) @ np.asarray(current).T)
    vel = np.zeros(3)
    mujoco.mju_quat2Vel(vel, quat, 1.0)
    return vel


def slerp(r0: np.ndarray, r1: np.ndarray, s: float) -> np.ndarray:
    """The rotation matrix a fraction `s` (0..1) of the way from `r0` to `r1`, along the shortest arc."""
    q0, q1 = matrix_to_quat(r0), matrix_to_quat(r1)
    dot = float(q0 @ q1)
    if dot < 0:
        q1, dot = -q1, -dot
    if dot > 0.9995:
        q = q0 + s * (q1 - q0)
    else:
        theta = math.acos(dot)
        q = (math.sin((1 - s) * theta) * q0 + math.sin(s * theta) * q1) / math.sin(theta)
    return quat_to_matrix(q / np.linalg.norm(q))


class WholeBodyIK:
    """Inverse kinematics of several ends of one tree of joints at once (a human's head, wrists and feet),
    each held at a position and an orientation: Blender's IK tree, as MORSE's human armature solved it.

        ik = WholeBodyIK(sim.model, servos, stiffness, rot_weight=3.0)
        q, errors = ik.solve(sim.data, [(body, pos, rot), ...])

    Each solve starts from the rest pose (joints at zero), as Blender's solver started each frame from the
    bones' own rotations, so a pose depends on where the targets are, not on the way they got there.
    Levenberg-Marquardt on the stacked Jacobians of the bodies; `stiffness` (one per joint, servos' order)
    weighs each joint's share of a movement: the step minimises |e - J dq|^2 + lambda^2 sum(stiffness dq^2)
    (Blender's IK stiffness). Returns joint values and, per target, (distance m, angle rad) left."""

    def __init__(self, model, servos, stiffness, rot_weight: float = 1.0):
        self.model = model
        self.servos = servos
        self.stiffness = np.asarray(stiffness, dtype=float)
        self.rot_weight = rot_weight
        self.scratch = mujoco.MjData(model)

    def _residual(self, data, goals, q) -> tuple[np.ndarray, list[tuple[float, float]]]:
        m, d = self.model, self.scratch
        d.qpos[self.servos.qpos] = q
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        parts, errors = [], []
        for body, pos, rot in goals:
            ep = np.asarray(pos, dtype=float) - d.xpos[body]
            er = rotation_error(rot, d.xmat[body].reshape(3, 3))
            parts += [ep, self.rot_weight * er]
            errors.append((float(np.linalg.norm(ep)), float(np.linalg.norm(er))))
        return np.concatenate(parts), errors

    def solve(self, data, goals, start=None, iterations: int = 150) -> tuple[np.ndarray, list[tuple[float, float]]]:
        m, servos = self.model, self.servos
        self.scratch.qpos[:] = data.qpos
        q = servos.clamp(np.zeros(len(servos.names)) if start is None else np.asarray(start, dtype=float))
        err, errors = self._residual(data, goals, q)
        cols = servos.dof
        jacp, jacr = np.zeros((3, m.nv)), np.zeros((3, m.nv))
        damping = IK_DAMPING
        for _ in range(iterations):
            rows = []
            for body, _, _ in goals:
                mujoco.mj_jacBody(m, self.scratch, jacp, jacr, body)
                rows += [jacp[:, cols], self.rot_weight * jacr[:, cols]]
            jac = np.vstack(rows)
            dq = np.linalg.solve(jac.T @ jac + damping ** 2 * np.diag(self.stiffness), jac.T @ err)
            biggest = float(np.max(np.abs(dq)))
            if biggest > IK_MAX_STEP:
                dq *= IK_MAX_STEP / biggest
            trial = servos.clamp(q + dq)
            new, new_errors = self._residual(data, goals, trial)
            if new @ new < err @ err:
                q, err, errors = trial, new, new_errors
                damping = max(IK_DAMPING, damping / 2)
                if biggest < 1e-7:
                    break
            else:
                damping *= 4
                if damping > IK_MAX_DAMPING:
                    break
                self._residual(data, goals, q)
        return q, errors
