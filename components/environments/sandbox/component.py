from morsec.component import Environment


class Sandbox(Environment):
    """An outdoor play area: flat ground at z = 0 enclosed by a low wall (inner faces at x = ±10 m and
    y = ±10 m, 0.5 m high), two crates, a concrete block, a pillar and a ramp, all static and away
    from the origin and the axes. MORSE's `sandbox`, the default of `morse create`."""

    short_descr = "Flat ground with obstacles inside a low wall"


COMPONENT = Sandbox
