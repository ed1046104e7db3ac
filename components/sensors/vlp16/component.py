"""MORSE's VLP16_180 builder (DepthCameraAggregator): three depth cameras side by side, 16 rows kept,
their points merged in the frame of the middle one."""

import math

import numpy as np
from pydantic import Field

from morsec.component import DataField, component_class
from morsec.kits.camera import (
    INTRINSIC_MATRIX,
    PICTURE_SIZE,
    CameraSensor,
    CameraView,
    b64,
    depth_points,
    optical_rotation,
    parse_keep_list,
    pixel_rays,
)

CAMERAS = 3
YAW_STEP = math.pi / 3.0  # camera i looks at azimuth (i - 1) * 60 deg: right, ahead, left
DepthCamera = component_class("sensors", "depth_camera")
VLP16_ROWS = "[1, 17, 34, 51, 68, 85, 102, 120, 137, 154, 171, 188, 205, 222, 239, 255]"


class VLP16(CameraSensor):
    """A Velodyne VLP-16 over 180 degrees, emulated as MORSE's VLP16_180: three depth cameras of 512 x 256
    pixels with a 27.7 mm lens (60 x 32.2 degrees each) at the component's origin, looking at azimuths
    -60 (camera 0, right), 0 (camera 1, ahead) and +60 degrees (camera 2, left); of each picture only the
    16 rows of `keep_list` are kept (about 2 degrees apart, as the VLP-16's 16 lasers), one point per
    pixel (`keep_resolution`: NaN where nothing was seen within 1..20 m). Every tick renders the three
    cameras and merges their points, camera 0 first, **in the optical frame of camera `master_camera`**
    (default 1, the middle one: x right, y down, z forward along the component's +x). Fields and socket
    message as depth_camera's (`points`, `nb_points`)."""

    short_descr = "VLP-16 over 180 deg: three depth cameras, 16 rows each, merged points"
    builder_name = "VLP16_180"
    frequency = 10.0

    class Properties(DepthCamera.Properties):
        cam_width: int = Field(512, ge=1, description="image width of each camera, pixels (read at start)")
        cam_height: int = Field(256, ge=1, description="image height of each camera, pixels (read at start)")
        cam_focal: float = Field(27.7, gt=0, description="focal length, mm (27.7: 60 degrees across 512 pixels)")
        keep_list: str = VLP16_ROWS
        keep_resolution: bool = True
        master_camera: int = Field(1, ge=0, le=2, description="the camera (0 right, 1 middle, 2 left) in whose "
                                   "optical frame the points are given")

    data = (
        DataField("points", None, "base64",
                  "nb_points x 3 float32: x, y, z in the master camera's optical frame (x right, y down, z "
                  "forward), m; camera 0's points first, each camera's kept rows in keep_list order, each row "
                  "left to right; on the wire base64 of nb_points * 12 bytes"),
        DataField("nb_points", 0, "int", "number of points (3 * cam_width * 16 with keep_resolution)"),
    )
    # see message(): the size and the intrinsic matrix of each camera
    message_fields = (*PICTURE_SIZE, *(f for f in data if f.name != "nb_points"), INTRINSIC_MATRIX)

    def start(self) -> None:
        super().start()
        p = self.properties
        self.views = [CameraView.of(self.sim, f"{self.name}.cam{i}", p) for i in range(CAMERAS)]
        v = self.views[0]
        self.rows = parse_keep_list(p.keep_list, v.height)
        self.rays = pixel_rays(v.width, v.height, v.fx, self.rows, p.Vertical_Flip)
        # camera i's optical frame -> the master's: turned by (i - master) * 60 deg
        self.to_master = [optical_rotation((i - p.master_camera) * YAW_STEP).astype(np.float32)
                          for i in range(CAMERAS)]
        self.local_data["points"] = np.zeros((0, 3), dtype=np.float32)

    def grab(self) -> None:
        p = self.properties
        clouds = []
        for view, rot in zip(self.views, self.to_master):
            points = depth_points(view.depth(p), self.rows, self.rays, p.cam_far, p.keep_resolution)
            clouds.append(points @ rot.T)
        points = np.ascontiguousarray(np.concatenate(clouds), dtype=np.float32)
        self.local_data["points"] = points
        self.local_data["nb_points"] = int(len(points))

    def message(self) -> dict:
        v = self.views[0]
        return {
            "timestamp": self.local_data["timestamp"],
            "height": v.height,
            "width": v.width,
            "points": b64(self.local_data["points"]),
            "intrinsic_matrix": v.matrix,
        }


COMPONENT = VLP16
