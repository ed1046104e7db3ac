"""Scene objects that an actuator moves to its goal as a visual marker (the `Target` of MORSE's Waypoint
and RotorcraftWaypoint). MORSE asked for such an object to have NO_COLLISION (its basic meshes had it), so
that the robot flying or driving to the goal does not run into its own marker; morsec's objects collide,
so the actuator makes its marker visual only: its geoms stop colliding and join the visual group, which
rays (laser scanners, the waypoint's radars) do not see."""

from __future__ import annotations

VISUAL_GROUP = 2  # geoms only drawn: not seen by rays (see the laser scanner)


def visual_marker(sim, name: str) -> int | None:
    """Body id of the scene object `name`, turned into a visual marker; None when there is no such object."""
    found = next((o for o in sim.objects if o.name == name), None)
    if found is None or found.body_id < 0:
        return None
    m = sim.model
    body = found.body_id
    for geom in range(m.ngeom):
        if m.body_rootid[m.geom_bodyid[geom]] == body or m.geom_bodyid[geom] == body:
            m.geom_contype[geom] = 0
            m.geom_conaffinity[geom] = 0
            m.geom_group[geom] = VISUAL_GROUP
    return body
