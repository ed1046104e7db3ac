"""Kits for components: geometry, geodesy, geomagnetism, cameras and rendering, inverse kinematics, joint servos.
Components (built-in and a user's own) import these; the runtime and the application use them too."""
