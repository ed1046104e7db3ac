import math

import mujoco
import numpy as np

from morsec.component import Actuator, ComponentProperties, DataField
from morsec.component.catalogue import load_class

ENGINE_SHARE = 0.4  # MORSE: each of the 4 wheels gets force * 0.4
BRAKE_SHARE = (0.1, 0.1, 1.3, 1.3)  # MORSE: brake * 0.1 on the front wheels, * 1.3 on the rear ones
BULLET_STEP = 1.0 / 60.0  # MORSE's Bullet vehicle takes the brake as an impulse per 1/60 s physics step
SIDE_RELAXATION = 0.2  # Bullet's tyre side friction: removes this share of a wheel's side slip per step
FORWARD_SLIP_FACTOR = 0.5  # Bullet: a wheel's forward impulse counts half towards its grip
MAX_SUSPENSION_FORCE = 6000.0  # Bullet's default cap of a wheel's suspension force, N
MAX_TRAVEL = 5.0  # Bullet's default suspension travel, m
MAX_RAY_HOPS = 4  # how many geoms that are not ground (the robot's own, drawn only) a ray may pass through


class SteerForce(Actuator):
    """Steering angle, engine force and brake of MORSE's Hummer, applied as MORSE's vehicle wrapper (Bullet's
    raycast vehicle) did: each wheel casts a ray down from its suspension's hard point; a wheel on the ground
    carries a spring-damper (stiffness and damping per unit of the car's mass, as Bullet's) and grips with
    Bullet's tyre model: its side slip is removed step by step, the engine pushes it along its heading, the
    brake stops it, all within its grip (tyre friction x load). The forces act on the chassis where the wheels
    touch the ground (the side forces, and the engine's and brake's, at the height of the chassis' centre of
    mass scaled by the roll influence). `steer` turns the front wheels (rad, positive to the left); `force`
    drives each wheel with force x 0.4 N (negative forward, as MORSE); `brake` brakes the front wheels with
    brake x 0.1 and the rear ones with brake x 1.3 (Bullet impulses per 1/60 s step).

    The robot class declares `vehicle_wheels` ((spin joint, steering joint or None, hard point), in MORSE's
    wheel order: front right, front left, rear right, rear left), `wheel_radius`, `suspension_rest_length`,
    `suspension_stiffness`, `suspension_damping`, `suspension_compression` and `roll_influence`; the robot's
    `friction` property is the tyres' friction slip."""

    short_descr = "Steering angle, engine force and brake of a car"
    builder_name = "SteerForce"
    frequency = 60.0

    robot_requires = ("vehicle_wheels", "wheel_radius", "suspension_rest_length", "suspension_stiffness",
                      "suspension_damping", "suspension_compression", "roll_influence")

    class Properties(ComponentProperties):
        pass

    data = (
        DataField("steer", 0.0, "float", "steering angle of the front wheels, rad (positive: to the left)"),
        DataField("force", 0.0, "float", "engine force, N, x 0.4 on each wheel (negative: forward)"),
        DataField("brake", 0.0, "float", "braking, x 0.1 on the front wheels, x 1.3 on the rear ones (Bullet "
                  "impulse per 1/60 s step)"),
    )

    def start(self):
        m = self.sim.model
        entry = next(r for r in self.sim.manifest.robots if r.name == self.robot.name)
        rc = load_class(entry.component)
        self.rc = rc
        self.chassis = self.robot.body_id
        self.bodies = {b for b in range(m.nbody) if _descends(m, b, self.chassis)}
        self.mass = float(m.body_subtreemass[self.chassis])
        self.slip = float(getattr(self.robot.properties, "friction", 200.0))

        def joint(name):
            if name is None:
                return None
            jid = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, f"{self.robot.name}/{name}")
            if jid < 0:
                raise RuntimeError(f"{self.name}: no joint {name} on robot {self.robot.name}")
            return int(m.jnt_qposadr[jid]), int(m.jnt_dofadr[jid])

        self.wheels = [(joint(spin), joint(steer), np.array(point, dtype=float))
                       for spin, steer, point in rc.vehicle_wheels]
        self.rotation = [0.0] * len(self.wheels)
        # the suspension carries the car now: the geoms it rests on without it (cylinders) stop colliding
        for g in range(m.ngeom):
            if m.geom_bodyid[g] == self.chassis and m.geom_type[g] == mujoco.mjtGeom.mjGEOM_CYLINDER:
                m.geom_contype[g] = 0
                m.geom_conaffinity[g] = 0
        self.last = None
        self.geomid = np.zeros(1, dtype=np.int32)
        self.normal = np.zeros(3)

    # ---------------------------------------------------------------- the raycast vehicle
    def _cast(self, start, down, length):
        """(distance, normal) of the ground under a wheel: the first colliding geom, not the robot's."""
        m, d = self.sim.model, self.sim.data
        point, travelled = start.copy(), 0.0
        for _ in range(MAX_RAY_HOPS):
            dist = mujoco.mj_ray(m, d, point, down, None, 1, self.chassis, self.geomid, self.normal)
            if dist < 0 or travelled + dist > length:
                return None
            g = int(self.geomid[0])
            if int(m.geom_bodyid[g]) in self.bodies or (m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0):
                travelled += dist + 1e-6
                point = start + down * travelled
                continue
            return travelled + dist, self.normal.copy()
        return None

    def default_action(self):
        m, d = self.sim.model, self.sim.data
        rc = self.rc
        dt = d.time - self.last if self.last is not None and d.time > self.last else m.opt.timestep * self.sim.substeps
        self.last = d.time
        steer = float(self.local_data["steer"])
        force = float(self.local_data["force"])
        brake = max(0.0, float(self.local_data["brake"]))
        b = self.chassis
        rot = d.xmat[b].reshape(3, 3)
        com = d.xipos[b].copy()
        vel = np.zeros(6)
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_BODY, b, vel, 0)
        w, v = vel[:3], vel[3:]
        irot = d.ximat[b].reshape(3, 3)
        inv_inertia = irot @ np.diag(1.0 / m.body_inertia[b]) @ irot.T
        up = rot[:, 2]
        down = -up
        radius, rest = rc.wheel_radius, rc.suspension_rest_length

        def velocity_at(p):
            return v + np.cross(w, p - com)

        def inv_mass_at(p, n):
            r = p - com
            return 1.0 / self.mass + n @ np.cross(inv_inertia @ np.cross(r, n), r)

        total_f, total_t = np.zeros(3), np.zeros(3)

        def push(f, at):
            nonlocal total_f, total_t
            total_f += f
            total_t += np.cross(at - com, f)

        contacts = []
        for _, steering, point in self.wheels:
            hard = d.xpos[b] + rot @ point
            hit = self._cast(hard, down, rest + radius)
            if hit is None:
                contacts.append(None)
                continue
            dist, normal = hit
            contact = hard + down * dist
            length = min(max(dist - radius, rest - MAX_TRAVEL), rest + MAX_TRAVEL)
            denominator = normal @ down
            if denominator >= -0.1:
                relative, inv = 0.0, 10.0
            else:
                inv = -1.0 / denominator
                relative = (normal @ velocity_at(contact)) * inv
            spring = rc.suspension_stiffness * (rest - length) * inv
            spring -= (rc.suspension_compression if relative < 0 else rc.suspension_damping) * relative
            load = max(0.0, spring * self.mass)
            push(normal * min(load, MAX_SUSPENSION_FORCE), contact)
            # the wheel's heading (the steered ones turned about the chassis' up axis) and axle on the ground
            angle = steer if steering is not None else 0.0
            heading = rot @ np.array([-math.sin(angle), math.cos(angle), 0.0])
            axle = np.cross(normal, heading)
            axle -= normal * (axle @ normal)
            axle /= np.linalg.norm(axle)
            forward = np.cross(axle, normal)
            contacts.append((contact, load, axle, forward))

        touching = sum(c is not None for c in contacts)
        grip_forces = []
        for k, c in enumerate(contacts):
            if c is None:
                grip_forces.append(None)
                continue
            contact, load, axle, forward = c
            side = -SIDE_RELAXATION * (axle @ velocity_at(contact)) / inv_mass_at(contact, axle) / dt
            if force != 0.0:
                along = -force * ENGINE_SHARE  # negative force drives forward, as MORSE's
            else:
                # the brake stops the wheel's share of the car, within the brake's impulse per Bullet step
                cap = brake * BRAKE_SHARE[min(k, len(BRAKE_SHARE) - 1)] / BULLET_STEP
                stop = -(forward @ velocity_at(contact)) / inv_mass_at(contact, forward) / touching / dt
                along = min(max(stop, -cap), cap)
            grip = load * self.slip
            demand = math.hypot(along * FORWARD_SLIP_FACTOR, side)
            if demand > grip:  # skidding: both shrink to the grip, as Bullet's
                along, side = along * grip / demand, side * grip / demand
            grip_forces.append((contact, axle * side + forward * along))

        roll = rc.roll_influence
        for c in grip_forces:
            if c is None:
                continue
            contact, f = c
            arm = contact - com
            arm -= up * ((up @ arm) * (1.0 - roll))  # roll influence: the tyre forces act nearer the centre
            push(f, com + arm)

        self.robot.apply_wrench(self.name, total_f, total_t)
        self._turn_wheels(steer, contacts, velocity_at, dt)

    def _turn_wheels(self, steer, contacts, velocity_at, dt):
        """Draw the wheels: the steered ones at the steering angle, each rolling with the ground under it."""
        d = self.sim.data
        for k, ((spin, steering, _), c) in enumerate(zip(self.wheels, contacts)):
            if steering is not None:
                d.qpos[steering[0]] = steer
                d.qvel[steering[1]] = 0.0
            if c is not None:
                contact, _, _, forward = c
                self.rotation[k] = (forward @ velocity_at(contact)) / self.rc.wheel_radius
            else:
                self.rotation[k] *= 0.99
            d.qpos[spin[0]] = math.remainder(d.qpos[spin[0]] - self.rotation[k] * dt, 2 * math.pi)
            d.qvel[spin[1]] = 0.0


def _descends(m, body: int, ancestor: int) -> bool:
    while body > 0:
        if body == ancestor:
            return True
        body = int(m.body_parentid[body])
    return body == ancestor


COMPONENT = SteerForce
