"""MORSE's DepthVideoCamera: a depth image in metres."""

from morsec.component import DataField
from morsec.component.catalogue import component_class
from morsec.kits.camera import INTRINSIC_MATRIX, PICTURE_SIZE, DepthCameraProperties

VideoCamera = component_class("sensors", "video_camera")


class DepthVideoCamera(VideoCamera):
    """A depth camera giving a depth *image*: for each pixel, the distance in metres **along the optical
    axis** (the component's +x; ROS REP 118's depth image), `cam_far` where nothing was seen between
    `cam_near` and `cam_far`. Socket message: `{timestamp, height, width, image: base64 float32,
    intrinsic_matrix}`. The kinect's `depth` half."""

    short_descr = "Depth camera: a depth image in metres (float32)"
    builder_name = "DepthVideoCamera"
    frequency = 20.0
    Properties = DepthCameraProperties

    data = (
        DataField("image", None, "base64",
                  "cam_height x cam_width float32 depth along the optical axis (planar: a wall facing the camera "
                  "reads the same in every pixel), m; cam_far where nothing was drawn between the clip planes; "
                  "first row at the bottom unless Vertical_Flip; on the wire base64 of its cam_width * cam_height "
                  "* 4 bytes (MORSE's buffer)"),
        INTRINSIC_MATRIX,
    )
    message_fields = (*PICTURE_SIZE, *data)

    def grab(self) -> None:  # the socket message is VideoCamera's, with float32 pixels
        self.local_data["image"] = self.view.depth(self.properties)


COMPONENT = DepthVideoCamera
