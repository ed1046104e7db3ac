"""`morsec run`: the MuJoCo loop, components, middlewares and services."""
