"""The example sweep's client (go_to_goal.yaml): steer the ATRV to (10, 0) on its pose sensor, noise and all,
then print the run's own metrics as a JSON object on the last line. `morsec sweep` gives it the run's ports
in its environment (MORSEC_SERVICE_PORT ...)."""

import json
import math
import os

from morsec.client import Morse

GOAL = (10.0, 0.0)
SPEED, GAIN = 2.0, 1.5  # m/s; rad/s per rad of heading error
PERIOD = 0.1  # simulated seconds between commands

with Morse("localhost", int(os.environ["MORSEC_SERVICE_PORT"])) as sim:
    commands, arrived = 0, False
    while sim.time() < float(os.environ["MORSEC_DURATION"]) - 1.0:
        pose = sim.robot.pose.get()
        dx, dy = GOAL[0] - pose["x"], GOAL[1] - pose["y"]
        if math.hypot(dx, dy) < 0.5:
            arrived = True
            break
        error = math.remainder(math.atan2(dy, dx) - pose["yaw"], math.tau)
        sim.robot.motion.publish({"v": SPEED, "w": GAIN * error})
        commands += 1
        sim.sleep(PERIOD)
    sim.robot.motion.publish({"v": 0.0, "w": 0.0})

print(json.dumps({"arrived": arrived, "commands": commands}))
