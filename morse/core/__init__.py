"""MORSE's core, for MORSE components written in MORSE's API (a `morse create` folder's src/<sim>/sensors and
actuators): `sensor.Sensor`, `actuator.Actuator`, `services`' decorators, `status`, `exceptions`, `blenderapi`
and `mathutils`, emulated on morsec's component contract and MuJoCo (see `emulation`). What they do not emulate
stops the build or the run with one line naming the component's file and line."""
