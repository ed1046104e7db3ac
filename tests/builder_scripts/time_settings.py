""" Time: strategy, main-loop rate, time scale, relative timestamps, physics sub-steps. """

from morse.builder import *

robot = ATRV()
motion = MotionVW()
motion.add_stream('socket')
robot.append(motion)

env = Environment('empty', fastmode = True)
env.set_time_strategy(TimeStrategies.FixedSimulationStep)
env.simulator_frequency(120)
env.set_time_scale(accelerate_by = 2.0)
env.use_relative_time(True)
env.set_physics_step_sub(4)
env.set_gravity(9.81)
env.create()
