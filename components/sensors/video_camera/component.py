"""MORSE's VideoCamera: RGBA pictures rendered by MuJoCo's offscreen renderer (see morsec/camera.py)."""

from morsec.component import DataField
from morsec.kits.camera import INTRINSIC_MATRIX, PICTURE_SIZE, CameraProperties, CameraSensor, CameraView, b64


class VideoCamera(CameraSensor):
    """A video camera: RGBA pictures of `cam_width` x `cam_height` pixels, looking along the component's
    +x axis, and the intrinsic matrix that goes with them (fx = fy = max(w, h) * cam_focal / 32, or from
    `cam_fov`; principal point at the image centre). `capture(n)` grabs n pictures then answers; the
    socket message is MORSE's `{timestamp, height, width, image: base64 RGBA, intrinsic_matrix}`, sent only
    on ticks that grabbed a picture. Renders without shadows or reflections unless `shadows` is on."""

    short_descr = "Video camera: RGBA pictures and their intrinsic matrix"
    builder_name = "VideoCamera"
    frequency = 20.0
    Properties = CameraProperties

    data = (
        DataField("image", None, "base64",
                  "the picture: cam_height x cam_width x 4 uint8, R G B A (alpha always 255), row after row: the "
                  "first row is the top of the picture unless Vertical_Flip is false (OpenGL's order); on the wire "
                  "base64 of its cam_width * cam_height * 4 bytes (MORSE's buffer)"),
        INTRINSIC_MATRIX,
    )
    message_fields = (*PICTURE_SIZE, *data)

    def start(self) -> None:
        super().start()
        self.view = CameraView.of(self.sim, self.name, self.properties)
        self.local_data["intrinsic_matrix"] = self.view.matrix

    def grab(self) -> None:
        self.local_data["image"] = self.view.rgba(self.properties)

    def message(self) -> dict:
        return {
            "timestamp": self.local_data["timestamp"],
            "height": self.view.height,
            "width": self.view.width,
            "image": b64(self.local_data["image"]),
            "intrinsic_matrix": self.local_data["intrinsic_matrix"],
        }


COMPONENT = VideoCamera
