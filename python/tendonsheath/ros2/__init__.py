"""ROS 2: a saved compensator as a node on the robot, the simulated drive as a node to try it
on, and the live loop recorded into a bag that ``ts.io.read_log`` reads.

The nodes need the ``ros2`` extra (rclpy and the message packages as pip wheels:
``pip install 'tendonsheath[ros2]'``); importing this package does not import rclpy, and a
node made without it raises :class:`~tendonsheath.MissingExtraError`, one line. The stepping
itself (:class:`LiveCompensator`, :class:`LivePlant`) is plain Python and runs without ROS.
See docs/ros2.md.
"""

from .compensator_node import compensator_node
from .live_compensator import Cycle, Limits, LiveCompensator, needed_inputs
from .live_plant import LivePlant, Reading, plant_source
from .plant_node import plant_node
from .recorder import BagRecorder
from .reference_node import reference_node, sine

__all__ = [
    "BagRecorder",
    "Cycle",
    "Limits",
    "LiveCompensator",
    "LivePlant",
    "Reading",
    "compensator_node",
    "needed_inputs",
    "plant_node",
    "plant_source",
    "reference_node",
    "sine",
]
