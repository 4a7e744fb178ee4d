"""Launch-monitor sessions as the devices and apps export them, and mcrun's own launch files.

- ``native``: mcrun's columns named with their unit (``ball_speed_mph``...), CSV or Parquet,
  the file checks every reader shares.
- ``formats``: the exports known (TrackMan plain and Normalized, Garmin R10, Rapsodo MLM2PRO,
  SkyTrak, FlightScope Mevo and Mevo+, Foresight FSX, Square Golf, Awesome Golf, GSPro Open
  Connect messages, one a line or in a connector's log): how each is recognised, where its
  quantities are and the source of their units.
- ``read``: a file into a ``Session`` (its own table, the launches and the device's results in
  SI, the club of each shot), the format detected from the header or forced.
"""

from mcrun.run.monitors.formats import FORMATS, NAMES, NATIVE
from mcrun.run.monitors.native import (
    FILE_COLUMNS,
    check_file,
    launch_columns,
    read_launch_table,
)
from mcrun.run.monitors.read import DEVICE, LAUNCH, Session, read_session, session_of_frame

__all__ = [
    "DEVICE",
    "FILE_COLUMNS",
    "FORMATS",
    "LAUNCH",
    "NAMES",
    "NATIVE",
    "Session",
    "check_file",
    "launch_columns",
    "read_launch_table",
    "read_session",
    "session_of_frame",
]
