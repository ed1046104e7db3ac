"""The environment's display settings (MORSE's show_framerate, show_physics, set_viewport, set_stereo, ...):
what each of morsec's ways of showing a scene does with each one, declared once in SETTINGS. The warning a
run prints at start, the MuJoCo options the viewers and `morsec render` set, and the table of
docs/running.md all come from here.

`environment` below is the scene's environment as plain data (the manifest's `scene.environment`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

# the ways a scene is shown, as the table's columns
RENDER, NATIVE, WEB, HEADLESS = "render", "native", "web", "headless"
SHOWN_BY = {RENDER: "`morsec render`", NATIVE: "`--view native`", WEB: "`--view web`", HEADLESS: "no viewer"}
IGNORED = "ignored"  # the setting is lost there: a run warns when the scene sets it
NA = "n/a"  # the setting means nothing there (a still picture has no frame rate): no warning

DEFAULT_SHADE = "MATERIAL"
STEREO_SHOWN = "SIDEBYSIDE"  # the one stereo mode MuJoCo draws in a picture (mjSTEREO_SIDEBYSIDE)
DEFAULT_CAMERA_SPEED = 2.0
DEFAULT_CLIP_END = 1000.0
SAME_AS_RENDER = "as in `morsec render`"
DOCS = "docs/running.md#display-settings"


@dataclass(frozen=True)
class Setting:
    name: str  # as the warning names it
    morse: str  # MORSE's builder call(s)
    is_set: Callable[[dict], bool]  # the scene asks for something (not the default)
    render: str
    native: str
    web: str
    headless: str

    def where(self, shown_by: str) -> str:
        return str(getattr(self, shown_by))


def _shade(env: dict) -> str:
    return "WIREFRAME" if env.get("fastmode") else str(env.get("viewport", {}).get("shade", DEFAULT_SHADE))


def _stereo(env: dict) -> str:
    return str(env.get("stereo", "NONE"))


SETTINGS: tuple[Setting, ...] = (
    Setting("camera", "set_camera_location / place_camera, set_camera_rotation / aim_camera, set_camera_clip, "
            "set_camera_focal_length", lambda env: True,  # shown wherever it means something
            render="the picture's viewpoint (unless `--camera`)",
            native="the window opens on it (Esc: MuJoCo's free camera)",
            web="the page opens on it",
            headless=NA),
    Setting("camera.speed", "set_camera_speed",
            lambda env: env.get("camera", {}).get("speed", DEFAULT_CAMERA_SPEED) != DEFAULT_CAMERA_SPEED,
            render=NA, native=IGNORED, web=IGNORED, headless=NA),
    # fastmode draws wireframes too, but asks above all for speed (MORSE's tests set it): no warning for it
    Setting("viewport.shade", "set_viewport(viewport_shade), Environment(fastmode=True)",
            lambda env: env.get("viewport", {}).get("shade", DEFAULT_SHADE) != DEFAULT_SHADE,
            render="drawn as the [mode](#viewport-modes) says", native="drawn as the mode says",
            web="drawn as the mode says", headless=IGNORED),
    Setting("viewport.clip_end", "set_viewport(clip_end=)",
            lambda env: env.get("viewport", {}).get("clip_end", DEFAULT_CLIP_END) != DEFAULT_CLIP_END,
            render=IGNORED, native=IGNORED, web=IGNORED, headless=IGNORED),
    Setting("show_framerate", "show_framerate", lambda env: bool(env.get("show_framerate")),
            render=NA, native="frame rate, simulated time and real-time factor, top right",
            web="the same, in the morsec panel", headless=IGNORED),
    Setting("show_physics", "show_physics", lambda env: bool(env.get("show_physics")),
            render="collision shapes (geom group 3), contact points and contact forces",
            native=SAME_AS_RENDER, web=SAME_AS_RENDER,
            headless=IGNORED),
    Setting("show_debug", "show_debug_properties / show_debug", lambda env: bool(env.get("show_debug")),
            render=NA, native="each robot's pose and each component's data (what it streams), bottom left",
            web="the same, in the morsec panel", headless=IGNORED),
    Setting("auto_start", "set_auto_start(False)", lambda env: not env.get("auto_start", True),
            render=NA, native="opens paused: space runs and pauses", web="opens paused: space or the panel's "
            "Run button runs and pauses", headless=IGNORED),
    Setting("fullscreen", "fullscreen", lambda env: bool(env.get("fullscreen")),
            render=NA, native="full-screen window (MuJoCo's F5; X11)", web=IGNORED, headless=IGNORED),
    Setting(f"stereo ({STEREO_SHOWN})", f"set_stereo('{STEREO_SHOWN}')", lambda env: _stereo(env) == STEREO_SHOWN,
            render="left and right eye side by side (mjSTEREO_SIDEBYSIDE)", native=IGNORED, web=IGNORED,
            headless=IGNORED),
    Setting("stereo", "set_stereo (other modes: ANAGLYPH, QUADBUFFERED, ABOVEBELOW, INTERLACED, VINTERLACE, "
            "DOME)", lambda env: _stereo(env) not in ("NONE", STEREO_SHOWN),
            render=IGNORED, native=IGNORED, web=IGNORED, headless=IGNORED),
    Setting("debug", "set_debug", lambda env: bool(env.get("debug")),
            render=NA, native="morsec's log at DEBUG level (stderr)", web="the same", headless="the same"),
)


@dataclass(frozen=True)
class Shade:
    meaning: str
    textures: bool = True
    lighting_effects: bool = True  # shadows and reflections
    wireframe: bool = False
    boxes_only: bool = False  # the bodies' bounding boxes instead of their shapes


SHADES: dict[str, Shade] = {
    "BOUNDBOX": Shade("each body's bounding box, no shapes (MuJoCo's body bounding volumes)", boxes_only=True),
    "WIREFRAME": Shade("wireframe (mjRND_WIREFRAME)", wireframe=True),
    "SOLID": Shade("lit colours without textures, shadows or reflections", textures=False,
                   lighting_effects=False),
    "TEXTURED": Shade("textures, without shadows or reflections", lighting_effects=False),
    "MATERIAL": Shade("MuJoCo's full rendering: textures, shadows, reflections (the default)"),
    "RENDERED": Shade("as MATERIAL"),
}


def ignored(environment: dict, shown_by: str) -> list[str]:
    """The settings the scene sets that `shown_by` (RENDER, NATIVE, WEB or HEADLESS) cannot show."""
    return [s.name for s in SETTINGS if s.is_set(environment) and s.where(shown_by) == IGNORED]


def warning(environment: dict, shown_by: str) -> str | None:
    """The one line a run prints at start about the settings it cannot show, or None."""
    names = ignored(environment, shown_by)
    if not names:
        return None
    names = [f"stereo ({_stereo(environment)})" if n == "stereo" else n for n in names]
    where = {HEADLESS: "a run without a viewer", RENDER: "morsec render", NATIVE: "--view native",
             WEB: "--view web"}[shown_by]
    return f"display settings {where} cannot show: {', '.join(names)} ({DOCS} says which viewer shows which)"


@dataclass
class Look:
    """MuJoCo's options for a scene's display settings: `option` (an MjvOption: geom groups and
    visualisation flags), `flags` (mjtRndFlag -> 0/1, set on the MjvScene) and `stereo` (an mjtStereo)."""

    option: Any
    flags: dict[int, int]
    stereo: int


def look(environment: dict) -> Look:
    import mujoco
    shade = SHADES[_shade(environment)]
    option = mujoco.MjvOption()
    vis, rnd = mujoco.mjtVisFlag, mujoco.mjtRndFlag
    option.flags[vis.mjVIS_TEXTURE] = int(shade.textures)
    if shade.boxes_only:
        option.geomgroup[:] = 0
        option.flags[vis.mjVIS_BODYBVH] = 1
    if environment.get("show_physics"):
        option.geomgroup[3] = 1
        option.flags[vis.mjVIS_CONTACTPOINT] = 1
        option.flags[vis.mjVIS_CONTACTFORCE] = 1
    flags = {int(rnd.mjRND_WIREFRAME): int(shade.wireframe), int(rnd.mjRND_SHADOW): int(shade.lighting_effects),
             int(rnd.mjRND_REFLECTION): int(shade.lighting_effects)}
    stereo = mujoco.mjtStereo.mjSTEREO_SIDEBYSIDE if _stereo(environment) == STEREO_SHOWN \
        else mujoco.mjtStereo.mjSTEREO_NONE
    return Look(option, flags, int(stereo))


def markdown() -> str:
    """The tables of docs/running.md's display section."""
    cols = (RENDER, NATIVE, WEB, HEADLESS)
    lines = ["| setting | MORSE | " + " | ".join(SHOWN_BY[c] for c in cols) + " |",
             "|---" * (2 + len(cols)) + "|"]
    for s in SETTINGS:
        lines.append(f"| `{s.name}` | {s.morse} | " + " | ".join(s.where(c) for c in cols) + " |")
    lines += ["", '<a id="viewport-modes"></a>', "", "| `viewport.shade` | drawn as |", "|---|---|"]
    lines += [f"| `{name}` | {shade.meaning} |" for name, shade in SHADES.items()]
    return "\n".join(lines) + "\n"
