""" Custom components the MORSE way (morse add sensor ...): SensorCreator / ActuatorCreator subclasses
with a _classpath. A classpath naming a catalogue component places that component. """

from morse.builder import *
from morse.builder.creator import ActuatorCreator, SensorCreator


class Mypose(SensorCreator):
    _classpath = "morse.sensors.pose.Pose"
    _blendname = "pose"

    def __init__(self, name=None):
        SensorCreator.__init__(self, name)
        self.frequency(20)

class Mymotion(ActuatorCreator):
    _classpath = "morse.actuators.v_omega.MotionVW"

    def __init__(self, name=None):
        ActuatorCreator.__init__(self, name)
        self.properties(ControlType = 'Velocity')

robot = ATRV()
sensor = Mypose()
sensor.add_stream('socket')
robot.append(sensor)
actuator = Mymotion('drive')
actuator.add_service('socket')
robot.append(actuator)

env = Environment('empty')
