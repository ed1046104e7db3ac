"""MORSE's DepthCamera: a depth picture turned into points in the camera's optical frame."""

import numpy as np
from pydantic import Field

from morsec.component import DataField
from morsec.component.catalogue import component_class
from morsec.kits.camera import (
    INTRINSIC_MATRIX,
    PICTURE_SIZE,
    DepthCameraProperties,
    b64,
    depth_points,
    parse_keep_list,
    pixel_rays,
)

VideoCamera = component_class("sensors", "video_camera")


class DepthCamera(VideoCamera):
    """A depth camera: the picture's depth buffer turned into 3-D points, one per pixel that saw something
    between `cam_near` and `cam_far`, **in the camera's optical frame: x right, y down, z forward** (z is
    the distance along the optical axis, the component's +x). `keep_list` keeps only some image rows (a
    sparse, lidar-like cloud); `keep_resolution` keeps one point per kept pixel (NaN where nothing was
    seen). Socket message: MORSE's `{timestamp, height, width, points: base64 float32 x, y, z, ...,
    intrinsic_matrix}`."""

    short_descr = "Depth camera: 3-D points (camera frame) from a rendered depth image"
    builder_name = "DepthCamera"
    frequency = 20.0

    class Properties(DepthCameraProperties):
        keep_list: str = Field("", description="image rows kept, e.g. '[1, 17, 34]' (or '1, 17, 34'), counted as "
                               "delivered: from the bottom unless Vertical_Flip; empty: every row. A few rows of a "
                               "wide camera emulate a multi-layer lidar (see vlp16)")
        keep_resolution: bool = Field(False, description="true: one point for every pixel of the kept rows, NaN "
                                      "(x, y, z) where nothing was seen (an organized cloud of cam_width x rows "
                                      "points); false: only the pixels that saw something")

    data = (
        DataField("points", None, "base64",
                  "nb_points x 3 float32: one point per pixel that saw something between cam_near and cam_far, "
                  "x, y, z in the camera's optical frame (x right, y down, z forward: z is the distance along the "
                  "optical axis, the component's +x), m; row by row in the image's row order (kept rows in "
                  "keep_list order), left to right; on the wire base64 of its nb_points * 12 bytes (MORSE's "
                  "buffer)"),
        DataField("nb_points", 0, "int", "number of points (at most cam_width * number of kept rows)"),
        INTRINSIC_MATRIX,
    )
    message_fields = (*PICTURE_SIZE, *(f for f in data if f.name != "nb_points"))  # see message()

    def start(self) -> None:
        super().start()
        p, v = self.properties, self.view
        self.rows = parse_keep_list(p.keep_list, v.height)
        self.rays = pixel_rays(v.width, v.height, v.fx, self.rows, p.Vertical_Flip)
        self._rows = None if self.rows == list(range(v.height)) else self.rows  # None: every row, no copy
        self.local_data["points"] = np.zeros((0, 3), dtype=np.float32)

    def grab(self) -> None:
        p = self.properties
        points = depth_points(self.view.depth(p), self._rows, self.rays, p.cam_far, p.keep_resolution)
        self.local_data["points"] = points
        self.local_data["nb_points"] = int(len(points))

    def message(self) -> dict:
        return {
            "timestamp": self.local_data["timestamp"],
            "height": self.view.height,
            "width": self.view.width,
            "points": b64(self.local_data["points"]),
            "intrinsic_matrix": self.local_data["intrinsic_matrix"],
        }


COMPONENT = DepthCamera
