from pydantic import Field

from morsec.component import Robot, RobotProperties


class Victim(Robot):
    """A human victim lying on the ground, waiting for help: MORSE's pseudo-robot of the ROSACE
    search-and-rescue scenario. It does not move (fixed where it is put, origin on the ground) and has no
    behaviour of its own; the `search_and_rescue` sensor of a robot finds it by its `Injured` property,
    reads its `Requirements` and `Severity`, and heals it."""

    short_descr = "Injured person lying on the ground, for the search-and-rescue sensor"
    builder_name = "Victim"
    xacro = "robot.urdf.xacro"
    static = True

    class Properties(RobotProperties):
        GroundRobot: bool = True
        Victim_Tag: bool = Field(True, description="marks the robot as a victim")
        Injured: bool = Field(True, description="the search-and-rescue sensor detects objects having this "
                              "property (whatever its value, as Blender's radar)")
        Requirements: str = Field("1,2,3", description="the abilities a robot needs to heal the victim, comma "
                                  "separated integers; healing removes those the robot has")
        Severity: int = Field(10, ge=0, description="how badly the victim is hurt; 0 once healed")


COMPONENT = Victim
