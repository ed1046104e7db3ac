"""The component contract (what a component folder's `component.py` declares) and the catalogue that
discovers component folders. Component authors import from here:

    from morsec.component import ComponentProperties, DataField, Level, Sensor, service
"""

from morsec.component.catalogue import component_class
from morsec.component.contract import (
                                       Actuator,
                                       Component,
                                       ComponentProperties,
                                       DataField,
                                       Device,
                                       Environment,
                                       Level,
                                       Prop,
                                       Robot,
                                       RobotProperties,
                                       SampledSensor,
                                       Sensor,
                                       body_position,
                                       body_rotation,
)
from morsec.component.fields import FIELD_TYPES
from morsec.component.properties import (
                                       ComputationModeProperties,
                                       ControlTypeProperties,
                                       GeomagneticDateProperties,
                                       RotorcraftProperties,
                                       WheeledRobotProperties,
)
from morsec.component.services import ServiceInfo, async_service, service

__all__ = ["Actuator", "Component", "ComponentProperties", "ComputationModeProperties", "ControlTypeProperties",
           "DataField", "Device", "Environment", "FIELD_TYPES", "GeomagneticDateProperties", "Level", "Prop", "Robot",
           "RobotProperties", "RotorcraftProperties", "SampledSensor", "Sensor", "ServiceInfo",
           "WheeledRobotProperties", "async_service", "body_position", "body_rotation", "component_class", "service"]
