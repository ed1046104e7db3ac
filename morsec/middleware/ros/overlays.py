"""MORSE's ROS overlays: a component's services adapted to ROS actions and topics (an overlay adapts one
component for one middleware; only services, never streams).

- ArmatureController (armatures): the joint trajectory interfaces of a ROS controller, under a namespace
  (default: the component's topic): actions `joint_trajectory_action` (control_msgs/JointTrajectoryAction,
  MORSE's) and `follow_joint_trajectory` (control_msgs/FollowJointTrajectoryAction), the topic `command`
  (trajectory_msgs/JointTrajectory), and for a one-joint armature (a torso lift) the action
  `position_joint_action` (control_msgs/SingleJointPositionAction); the parameter `<namespace>/joints`.
  Each goal becomes a call of the armature's `trajectory` service.
- WayPoint (waypoint): the action `<namespace>/move_base` (move_base_msgs/MoveBaseAction): a goal becomes
  the waypoint's `goto`.

A goal arrives on a rospy thread; it is started on the loop's thread (RosNode.call_soon). A new goal
preempts the one in progress; a cancelled goal cancels its request (the component stops)."""

from __future__ import annotations

import logging
from typing import Any

import actionlib
import rospy
from trajectory_msgs.msg import JointTrajectory

from morsec.component.services import FAILED, PREEMPTED, SUCCESS
from morsec.middleware.ros.serialisers import default_topic

log = logging.getLogger("morsec.middleware.ros")

# wall-clock s between the frame that ends a goal and its result: a client that reads a topic once its
# action is done (wait for the result, then check the joint states) has that frame's messages by then, even
# in fixed_step, where the next frames follow within microseconds and its subscribers' threads lag a little
RESULT_GAP = 0.1


class ActionOverlay:
    """The common part: action servers whose goals become service requests, one at a time."""

    def __init__(self, node, component: str, instance: Any, namespace: str | None = None):
        self.node = node
        self.component = component
        self.instance = instance
        self.namespace = (namespace or default_topic(component)).rstrip("/")
        self.servers: list[actionlib.ActionServer] = []
        self.names: list[str] = []
        self.active: tuple[Any, Any] | None = None  # (goal handle or None for a topic, request)

    def action(self, name: str, spec, start, result=None) -> None:
        """Serve action `name` (under the namespace): `start(goal)` returns (service, args) for a goal."""
        full = f"{self.namespace}/{name}"

        def on_goal(handle):
            self.node.call_soon(lambda: self._begin(handle, start, result))

        def on_cancel(handle):
            self.node.call_soon(lambda: self._cancel(handle))

        server = actionlib.ActionServer(full, spec, on_goal, on_cancel, auto_start=False)
        server.start()
        self.servers.append(server)
        self.names.append(f"{full} ({spec._type})")

    # ---- on the loop's thread
    def _begin(self, handle, start, result) -> None:
        try:
            service, args = start(handle.get_goal() if handle is not None else None)
        except ValueError as err:
            if handle is not None:
                handle.set_rejected(text=str(err))
            log.warning("%s: %s", self.component, err)
            return
        self._preempt()
        if handle is not None:
            handle.set_accepted()

        def done(status: str, value: Any) -> None:
            if self.active is not None and self.active[0] is handle:
                self.active = None
            if handle is not None:
                self.node.call_later(RESULT_GAP, lambda: answer(status, value))

        def answer(status: str, value: Any) -> None:
            try:
                if status == SUCCESS:
                    handle.set_succeeded(result() if result else None)
                elif status == PREEMPTED:
                    handle.set_canceled()
                elif status == FAILED:
                    handle.set_aborted(text=str(value))
            except Exception as err:  # the goal's state moved on meanwhile (cancelled by its client)
                log.debug("%s: goal already finished: %s", self.component, err)

        request = self.node.call(self.component, service, args, done, client=self)
        # running, or waiting for the end of the next frame to start (MORSE's frame order): cancelled either way
        if self.node.context.requests.pending(request):
            self.active = (handle, request)

    def _preempt(self) -> None:
        if self.active is not None:
            _, request = self.active
            self.active = None
            self.node.cancel(self, request)

    def _cancel(self, handle) -> None:
        # actionlib hands a new handle object for the same goal to the cancel callback: goals are told by id
        if self.active is not None and self.active[0] is not None and _goal_id(self.active[0]) == _goal_id(handle):
            self._preempt()
        else:
            try:
                handle.set_canceled()
            except Exception:
                pass

    def topic(self, name: str, message_class, start) -> None:
        """Subscribe to `name` (under the namespace): each message is a goal with no one to answer."""
        full = f"{self.namespace}/{name}"
        self.node.subscriber(full, message_class,
                             lambda msg: self.node.call_soon(lambda: self._begin(None, lambda _g: start(msg), None)))
        self.names.append(f"{full} ({message_class._type}, in)")

    def describe(self) -> list[str]:
        return list(self.names)

    def close(self) -> None:
        self.servers = []


def _goal_id(handle) -> str:
    return handle.get_goal_id().id


class ArmatureController(ActionOverlay):
    """MORSE's armatures.ArmatureController: a ROS joint trajectory controller of an armature."""

    def __init__(self, node, component: str, instance: Any, namespace: str | None = None):
        super().__init__(node, component, instance, namespace)
        from control_msgs.msg import (
            FollowJointTrajectoryAction,
            FollowJointTrajectoryResult,
            JointTrajectoryAction,
            SingleJointPositionAction,
        )
        self.joints = list(instance.names)
        rospy.set_param(self.namespace + "/joints", self.joints)
        rospy.set_param(self.namespace + "/joint_trajectory_action/joints", self.joints)
        self.action("joint_trajectory_action", JointTrajectoryAction, lambda g: self._trajectory(g.trajectory))
        self.action("follow_joint_trajectory", FollowJointTrajectoryAction, lambda g: self._trajectory(g.trajectory),
                    result=lambda: FollowJointTrajectoryResult(error_code=FollowJointTrajectoryResult.SUCCESSFUL))
        self.topic("command", JointTrajectory, self._trajectory)
        if len(self.joints) == 1:
            self.action("position_joint_action", SingleJointPositionAction, self._position)

    def _current(self) -> dict[str, float]:
        """Where each joint is going (the armature's targets: where it is at rest)."""
        return {j: float(self.instance.local_data.get(j, 0.0)) for j in self.joints}

    def _trajectory(self, trajectory) -> tuple[str, list]:
        """A ROS JointTrajectory -> the armature's `trajectory` (MORSE's format): positions in the armature's
        order, joints the trajectory leaves out staying where they are going."""
        names = list(trajectory.joint_names)
        unknown = sorted(set(names) - set(self.joints))
        if unknown:
            raise ValueError(f"the trajectory names joints {', '.join(unknown)}, which {self.component} does not "
                             f"have (it has: {', '.join(self.joints)})")
        current = self._current()
        points = []
        for p in trajectory.points:
            given = dict(zip(names, p.positions))
            points.append({"positions": [float(given.get(j, current[j])) for j in self.joints],
                           "time_from_start": p.time_from_start.to_sec()})
        if not points:
            raise ValueError("the trajectory has no points")
        stamp = trajectory.header.stamp.to_sec()
        return "trajectory", [{"starttime": stamp if stamp > 0 else None, "points": points}]

    def _position(self, goal) -> tuple[str, list]:
        """SingleJointPosition: to `position` in at least `min_duration`, at most at `max_velocity`."""
        joint = self.joints[0]
        target = float(goal.position)
        distance = abs(target - self._current()[joint])
        duration = goal.min_duration.to_sec()
        if goal.max_velocity > 0:
            duration = max(duration, distance / float(goal.max_velocity))
        return "trajectory", [{"points": [{"positions": [target], "time_from_start": duration}]}]


class WayPoint(ActionOverlay):
    """MORSE's waypoints.WayPoint: move_base_msgs/MoveBaseAction on `<namespace>/move_base`."""

    def __init__(self, node, component: str, instance: Any, namespace: str | None = None):
        super().__init__(node, component, instance, namespace)
        from move_base_msgs.msg import MoveBaseAction
        self.action("move_base", MoveBaseAction, self._goto)

    def _goto(self, goal) -> tuple[str, list]:
        p = goal.target_pose.pose.position
        return "goto", [float(p.x), float(p.y), float(p.z)]
