"""tools/conformance_page.py: the page says the pass rate and, for each failing file, why (from its log)."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
spec = importlib.util.spec_from_file_location("conformance_page", ROOT / "tools" / "conformance_page.py")
tool = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tool)


def test_the_page_gives_the_rate_and_each_failure_with_its_reason(tmp_path):
    (tmp_path / "base__vw_testing.py.log").write_text(
        "FAIL: test_vw_controller (__main__.VW_Test.test_vw_controller)\n"
        "Traceback (most recent call last):\n"
        "AssertionError: -0.19 != 0.0 within 0.1 delta\n")
    output = (f"logs: {tmp_path}\n"
              "base/pose_testing.py                           6   0  \n"
              "base/vw_testing.py                             2   2  FAIL: test_vw_controller (__main__.VW_Test)\n"
              "robots/segway/spiral.py                        0   2  ERROR: test_vw_controller\n"
              "8 passed, 4 failed\n")
    page = tool.page(output, ["base", "robots"])
    assert "**8 passed, 4 failed** (67% of the tests; 1 of 3 files pass whole)." in page
    assert "| `base/vw_testing.py` | 2 | 2 | AssertionError: -0.19 != 0.0 within 0.1 delta |" in page
    assert "| `robots/segway/spiral.py` | 0 | 2 | calls `Morse.stream`" in page  # the exception
    assert "- `base/pose_testing.py` (6)" in page


def test_the_check_names_a_file_recorded_as_passing_that_fails_or_is_missing():
    page = ("## Files with failures\n\n| `base/vw_testing.py` | 2 | 2 | x |\n\n"
            "## Files that pass\n\n- `base/pose_testing.py` (6)\n- `base/sick_testing.py` (2)\n"
            "- `base/gps_testing.py` (2)\n\n## Not measured by the suite\n\n- `base/video_camera_testing.py` x\n")
    output = ("base/pose_testing.py                           6   0  \n"
              "base/sick_testing.py                           1   1  FAIL: test_sick\n"
              "base/vw_testing.py                             2   2  FAIL: test_vw_controller\n"
              "9 passed, 3 failed\n")
    assert tool.recorded_passing(page) == ["base/pose_testing.py", "base/sick_testing.py", "base/gps_testing.py"]
    # sick fails, gps gave no result; vw was already failing and the video camera is not a result
    assert tool.regressions(output, page) == ["base/sick_testing.py", "base/gps_testing.py"]


def test_the_reason_is_unittests_first_failure_not_an_error_a_clients_thread_printed_before(tmp_path):
    (tmp_path / "base__gps_testing.py.log").write_text(
        "Exception in thread Thread-3:\nValueError: list.remove(x): x not in list\n"
        "FAIL\n======\nFAIL: test_waypoint_services (__main__.Waypoints_Test.test_waypoint_services)\n"
        "Traceback (most recent call last):\nAssertionError: 5.24 != 5.21 within 0.03 delta\n")
    output = (f"logs: {tmp_path}\nbase/gps_testing.py                       2   2  ValueError: list.remove\n"
              "2 passed, 2 failed\n")
    assert "| `base/gps_testing.py` | 2 | 2 | AssertionError: 5.24 != 5.21 within 0.03 delta |" in tool.page(output, ["base"])
