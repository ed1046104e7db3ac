"""MORSE's Kinect: an RGB camera and a depth camera side by side, grabbed together."""

from pydantic import Field, model_validator

from morsec.component import DataField, component_class
from morsec.kits.camera import CameraProperties, CameraSensor, CameraView, b64

IDENTITY = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
PARTS = {"rgb": "video_camera", "depth": "depth_video_camera"}  # each part of the message: that camera's message


class Kinect(CameraSensor):
    """Microsoft Kinect RGB-D sensor, as MORSE's `Kinect` builder: a video camera (`rgb`, 128 x 128 RGBA,
    8 cm to the left of the component's origin) and a depth camera (`depth`, 128 x 128 float32 depth in
    metres along the optical axis, 8 cm to the right), both 6 cm forward and 4 cm up, looking along the
    component's +x with the same lens. MORSE builds it as a compound of two child cameras; here one
    component renders both at each tick and `local_data` holds both, as a compound sensor does:
    `{timestamp, rgb: {image, intrinsic_matrix}, depth: {image, intrinsic_matrix}}`. `capture(n)` grabs
    n pairs. Socket message: `{timestamp, rgb: <video_camera message>, depth: <depth_video_camera
    message>}` (pictures in base64). cam_near / cam_far clip the RGB picture, depth_near / depth_far the
    depth one (MORSE's depth camera defaults, 1 and 20 m)."""

    short_descr = "Kinect RGB-D: a video camera and a depth camera, 128 x 128, grabbed together"
    builder_name = "Kinect"
    frequency = 20.0

    class Properties(CameraProperties):
        cam_width: int = Field(128, ge=1, description="image width of both cameras, pixels (read at start)")
        cam_height: int = Field(128, ge=1, description="image height of both cameras, pixels (read at start)")
        depth_near: float = Field(1.0, gt=0, description="near clipping distance of the depth camera, m")
        depth_far: float = Field(20.0, gt=0, description="far clipping distance of the depth camera, m (the depth "
                                 "of pixels that saw nothing)")

        @model_validator(mode="after")
        def _depth_clip_planes(self):
            if self.depth_far <= self.depth_near:
                raise ValueError(f"depth_far ({self.depth_far}) must be larger than depth_near ({self.depth_near})")
            return self

    data = (
        DataField("rgb", {"image": None, "intrinsic_matrix": IDENTITY}, "dict",
                  "the RGB camera: image (cam_height x cam_width x 4 uint8 RGBA) and intrinsic_matrix"),
        DataField("depth", {"image": None, "intrinsic_matrix": IDENTITY}, "dict",
                  "the depth camera: image (cam_height x cam_width float32, m along the optical axis; depth_far "
                  "where nothing was seen) and intrinsic_matrix"),
    )
    # see message(): each camera's part is that camera's own message
    message_fields = (
        DataField("rgb", {}, "dict", "the RGB camera's picture, as a video_camera message"),
        DataField("depth", {}, "dict", "the depth camera's picture, as a depth_video_camera message"),
    )
    @classmethod
    def message_schema(cls, level=None) -> dict:
        schema = super().message_schema(level)
        for name, camera in PARTS.items():
            part = component_class("sensors", camera).message_schema()
            part.pop("title", None)
            part["description"] = schema["properties"][name]["description"]
            schema["properties"][name] = part
        return schema

    def start(self) -> None:
        super().start()
        p = self.properties
        self.rgb_view = CameraView.of(self.sim, f"{self.name}.rgb", p)
        self.depth_view = CameraView.of(self.sim, f"{self.name}.depth", p)
        self.local_data["rgb"] = {"image": None, "intrinsic_matrix": self.rgb_view.matrix}
        self.local_data["depth"] = {"image": None, "intrinsic_matrix": self.depth_view.matrix}

    def grab(self) -> None:
        p = self.properties
        depth_props = p.model_copy(update={"cam_near": p.depth_near, "cam_far": p.depth_far, "shadows": False})
        self.local_data["rgb"] = {"image": self.rgb_view.rgba(p), "intrinsic_matrix": self.rgb_view.matrix}
        self.local_data["depth"] = {"image": self.depth_view.depth(depth_props),
                                    "intrinsic_matrix": self.depth_view.matrix}

    def _part(self, name: str, view: CameraView) -> dict:
        part = self.local_data[name]
        return {"timestamp": self.local_data["timestamp"], "height": view.height, "width": view.width,
                "image": b64(part["image"]), "intrinsic_matrix": part["intrinsic_matrix"]}

    def message(self) -> dict:
        return {"timestamp": self.local_data["timestamp"], "rgb": self._part("rgb", self.rgb_view),
                "depth": self._part("depth", self.depth_view)}


COMPONENT = Kinect
