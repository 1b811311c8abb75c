"""read_log on real ROS bags written with the rosbags writer (ROS 1, ROS 2 sqlite3 and MCAP):
values, time bases (header stamps, receive time), the alignment of two topics at different
rates against a closed form, and the one-line errors."""

import sys

import numpy as np
import pytest
from _rosbag_helpers import (
    EPOCH_NS,
    KINDS,
    float64,
    joint_state,
    point_stamped,
    pose_stamped,
    storage_file,
    write_bag,
)

from tendonsheath import io

# (kind, whether to give the ROS 2 storage file rather than the bag folder)
FORMS = [("ros1", False), ("sqlite3", False), ("sqlite3", True), ("mcap", False), ("mcap", True)]
FORM_IDS = ["ros1", "sqlite3-folder", "db3-file", "mcap-folder", "mcap-file"]


def _bag(tmp_path, kind, topics, as_file=False, name="run"):
    path = write_bag(tmp_path / name, kind, topics)
    return storage_file(path) if as_file else path


def _stamps(rng, rate, start_s, duration_s):
    n = int(duration_s * rate)
    return EPOCH_NS + np.round((start_s + np.arange(n) / rate) * 1e9).astype(np.int64)


@pytest.mark.parametrize(("kind", "as_file"), FORMS, ids=FORM_IDS)
@pytest.mark.parametrize("seed", range(3))
def test_two_rates_align_on_the_output_stamps_with_a_ramp_input_exact(
    tmp_path, kind, as_file, seed
):
    """Input a ramp in time on a JointState topic, output on a PointStamped topic at another
    rate: linear interpolation is exact for a ramp, so x at every output stamp is the closed
    form; output messages outside the input's span are dropped, and counted."""
    rng = np.random.default_rng(seed)
    rate_in, rate_out = rng.uniform(50, 400), rng.uniform(20, 300)
    in_ns = _stamps(rng, rate_in, rng.uniform(0, 0.05), 1.0)
    out_ns = _stamps(rng, rate_out, rng.uniform(0, 0.05), 1.0)
    c0, c1 = rng.uniform(-1, 1), rng.uniform(-3, 3)

    def ramp(ns):
        return c0 + c1 * (ns - EPOCH_NS) * 1e-9

    y_all = np.cos(7.0 * (out_ns - EPOCH_NS) * 1e-9)
    latency = int(rng.uniform(1e6, 3e6))  # receive time lags the header stamp
    topics = {
        "/motor/joint_states": [(s + latency, joint_state(kind, s, [ramp(s), 5.0])) for s in in_ns],
        "/tip/point": [
            (s + latency, point_stamped(kind, s, y, 2.0))
            for s, y in zip(out_ns, y_all, strict=True)
        ],
    }
    log = io.read_log(
        _bag(tmp_path, kind, topics, as_file),
        input="/motor/joint_states:position[0]",
        output="/tip/point:point.x",
    )
    inside = (out_ns >= in_ns[0]) & (out_ns <= in_ns[-1])
    kept = out_ns[inside]
    np.testing.assert_array_equal(log.t, (kept - kept[0]) * 1e-9)
    np.testing.assert_allclose(log.x, ramp(kept), rtol=0, atol=1e-9)
    np.testing.assert_array_equal(log.y, y_all[inside])
    np.testing.assert_array_equal(log.rows, np.flatnonzero(inside) + 1)
    text = " | ".join(log.notes)
    assert "time of /tip/point: its header stamps" in text
    assert "time of /motor/joint_states: its header stamps" in text
    assert f"stamp {kept[0] // 10**9}.{kept[0] % 10**9:09d} s" in text
    if not inside.all():
        before, after = int((out_ns < in_ns[0]).sum()), int((out_ns > in_ns[-1]).sum())
        assert (
            f"{before + after} of {out_ns.size} messages of /tip/point lie outside the time "
            f"span of /motor/joint_states: dropped (before its first message: {before}, "
            f"after its last: {after})"
        ) in text


@pytest.mark.parametrize("kind", KINDS)
def test_sine_input_interpolation_error_within_the_closed_form_bound(tmp_path, kind):
    """Linear interpolation of sin(w t) sampled every h errs by at most h^2 w^2 / 8."""
    rng = np.random.default_rng(7)
    w, rate_in = 2 * np.pi * 3.0, 200.0
    in_ns = _stamps(rng, rate_in, 0.0, 1.0)
    out_ns = _stamps(rng, 77.0, 0.003, 0.9)

    def sine(ns):
        return np.sin(w * (ns - EPOCH_NS) * 1e-9)

    topics = {
        "/cmd": [(s, float64(kind, sine(s))) for s in in_ns],
        "/tip": [(s, float64(kind, 0.0)) for s in out_ns],
    }
    log = io.read_log(_bag(tmp_path, kind, topics), input="/cmd", output="/tip:data")
    err = np.max(np.abs(log.x - sine(out_ns)))
    bound = (1.0 / rate_in) ** 2 * w**2 / 8
    assert 0 < err <= bound * (1 + 1e-6)
    assert "time of /cmd: the bag's receive time (no header)" in log.notes[1:]


@pytest.mark.parametrize("kind", KINDS)
def test_receive_time_without_a_header_and_when_the_stamps_are_zero(tmp_path, kind):
    receive = EPOCH_NS + np.array([0, 10, 21, 30, 42]) * 1_000_000
    topics = {
        "/a": [(r, float64(kind, k)) for k, r in enumerate(receive)],
        "/b": [(r, point_stamped(kind, 0, 2.0 * k)) for k, r in enumerate(receive)],
    }
    log = io.read_log(_bag(tmp_path, kind, topics), input="/a", output="/b:point.x")
    np.testing.assert_array_equal(log.t, (receive - receive[0]) * 1e-9)
    np.testing.assert_allclose(log.x, np.arange(5.0))
    np.testing.assert_allclose(log.y, 2.0 * np.arange(5.0))
    assert "time of /b: the bag's receive time (its header stamps are zero)" in log.notes
    with pytest.raises(ValueError, match=r"topic /a \(std_msgs/msg/Float64\) has no header"):
        io.read_log(_bag(tmp_path, kind, topics, name="again"), input="/a", time="header")


@pytest.mark.parametrize("kind", KINDS)
def test_time_receive_and_time_field_override_the_header(tmp_path, kind):
    stamp = EPOCH_NS + np.arange(6) * 5_000_000
    receive = stamp + np.array([3, 1, 4, 1, 5, 9]) * 100_000
    msgs = [joint_state(kind, s, [k, -k, 0.25 * k]) for k, s in enumerate(stamp)]
    path = _bag(tmp_path, kind, {"/js": list(zip(receive, msgs, strict=True))})
    both = {"input": "/js:position[0]", "output": "/js:position[1]"}
    log = io.read_log(path, **both)
    np.testing.assert_array_equal(log.t, (stamp - stamp[0]) * 1e-9)
    np.testing.assert_array_equal(log.y, -log.x)
    log = io.read_log(path, time="receive", **both)
    np.testing.assert_array_equal(log.t, (receive - receive[0]) * 1e-9)
    assert "time of /js: the bag's receive time" in log.notes
    log = io.read_log(path, time="/js:header.stamp", **both)
    np.testing.assert_array_equal(log.t, (stamp - stamp[0]) * 1e-9)
    log = io.read_log(path, time="/js:position[2]", **both)  # a number of seconds
    np.testing.assert_allclose(log.t, 0.25 * np.arange(6.0), rtol=0, atol=1e-12)
    assert "time of /js: its field position[2]" in log.notes


@pytest.mark.parametrize("kind", KINDS)
def test_out_of_order_stamps_are_sorted_and_a_nested_field_is_read(tmp_path, kind):
    stamps = EPOCH_NS + np.array([0, 20, 10, 30, 40]) * 1_000_000  # message 3 stamped early
    topics = {
        "/pose": [
            (EPOCH_NS + k * 10_000_000 + 5, pose_stamped(kind, s, 0.1 * k))
            for k, s in enumerate(stamps)
        ],
    }
    log = io.read_log(_bag(tmp_path, kind, topics), input="/pose:pose.position.x")
    np.testing.assert_allclose(log.t, [0, 0.01, 0.02, 0.03, 0.04])
    np.testing.assert_allclose(log.x, [0.0, 0.2, 0.1, 0.3, 0.4])
    np.testing.assert_array_equal(log.rows, [1, 3, 2, 4, 5])
    assert "2 message(s) of /pose out of order by stamp: sorted by stamp" in log.notes


def _simple(tmp_path, kind="ros1", n=5, name="run"):
    ns = EPOCH_NS + np.arange(n) * 10_000_000
    topics = {
        "/js": [(s, joint_state(kind, s, [0.1 * k, 1.0])) for k, s in enumerate(ns)],
        "/f": [(s + 1, float64(kind, k)) for k, s in enumerate(ns)],
    }
    return _bag(tmp_path, kind, topics, name=name)


ERRORS = [
    (
        {"input": "/nope:data"},
        r"run.bag: no input topic '/nope'; topics: /f \(std_msgs/msg/Float64, 5 messages\), "
        r"/js \(sensor_msgs/msg/JointState, 5 messages\)$",
    ),
    (
        {"input": "/js:pos"},
        r"topic /js \(sensor_msgs/msg/JointState\): no input field 'pos' \(pos has no such "
        r"field\); fields: header.seq, header.stamp.sec, header.stamp.nanosec, position\[0\], "
        r"position\[1\]$",
    ),
    ({"input": "/js:position[2]"}, r"position\[2\] has 2 item\(s\), no index 2\); fields: "),
    ({"input": "/js"}, r"/js \(sensor_msgs/msg/JointState\) holds more than one number"),
    ({"input": "/js:position"}, r"'position' is an array of 2 \(give an index"),
    ({"input": "/js:header"}, r"'header' is a std_msgs/msg/Header message, not a number"),
    ({"input": "/f", "output": "/js:name[0]"}, r"output field 'name\[0\]' is text"),
    ({"input": "/js:position[0", "output": "/f"}, r"'position\[0' is not a field path"),
    ({"input": None}, r"run.bag: name the input as /topic:field; topics: /f \(std_msgs"),
    ({"input": "/f", "time": "t"}, r"time must be 'header', 'receive' or /topic:field"),
    ({"input": "/f", "time": "/js:header.stamp"}, r"time topic /js must be the input's or"),
    ({"input": "/f", "curve_angle": "/theta:data"}, r"no curve angle topic '/theta'"),
    (
        {"input": "/js:position[0]", "time": "/js:name[0]"},
        r"run.bag: topic /js, message 1: the time field 'name\[0\]' is neither a "
        r"builtin_interfaces/msg/Time nor a number of seconds$",
    ),
    (
        {"input": "/js:position[0]", "time": "/js:position[7]"},
        r"run.bag: topic /js, message 1: time field position\[7\] has 2 item\(s\), no index 7$",
    ),
]


@pytest.mark.parametrize(("kwargs", "pattern"), ERRORS)
def test_bad_names_get_one_line_errors_listing_topics_and_fields(tmp_path, kwargs, pattern):
    with pytest.raises(ValueError, match=pattern) as info:
        io.read_log(_simple(tmp_path), **kwargs)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("kind", KINDS)
def test_a_message_with_a_shorter_array_or_a_nan_is_named(tmp_path, kind):
    ns = EPOCH_NS + np.arange(6) * 10_000_000
    pos = [[0.0, 1.0]] * 3 + [[0.5]] + [[0.0, 1.0]] * 2
    topics = {"/js": [(s, joint_state(kind, s, p)) for s, p in zip(ns, pos, strict=True)]}
    with pytest.raises(ValueError, match=r"topic /js, message 4: position\[1\] has 1 item"):
        io.read_log(_bag(tmp_path, kind, topics), input="/js:position[1]")
    values = [0.0, 1.0, np.nan, 3.0, 4.0, 5.0]
    topics = {"/x": [(s, float64(kind, v)) for s, v in zip(ns, values, strict=True)]}
    path = _bag(tmp_path, kind, topics, name="nan")
    with pytest.raises(ValueError, match=r"topic /x, message 3: the input data is nan, not a"):
        io.read_log(path, input="/x")
    log = io.read_log(path, input="/x", missing="drop")
    np.testing.assert_array_equal(log.x, [0, 1, 3, 4, 5])
    assert "1 message(s) with a missing value dropped: messages 3" in log.notes
    log = io.read_log(path, input="/x", missing="interpolate")
    np.testing.assert_allclose(log.x, np.arange(6.0))


def test_topics_that_do_not_overlap_in_time(tmp_path):
    topics = {
        "/a": [(EPOCH_NS + k * 1_000_000, float64("ros1", k)) for k in range(5)],
        "/b": [(EPOCH_NS + 10**9 + k * 1_000_000, float64("ros1", k)) for k in range(5)],
    }
    with pytest.raises(ValueError, match=r"the topics /b and /a do not overlap in time"):
        io.read_log(_bag(tmp_path, "ros1", topics), input="/a", output="/b")


def test_topics_that_each_overlap_the_output_but_not_each_other(tmp_path):
    def stream(first, count):
        return [(EPOCH_NS + (first + k) * 10**7, float64("ros1", k)) for k in range(count)]

    topics = {"/y": stream(0, 30), "/x": stream(0, 10), "/theta": stream(20, 10)}
    with pytest.raises(ValueError, match=r"no message of /y lies within the time span of every"):
        io.read_log(_bag(tmp_path, "ros1", topics), input="/x", output="/y", curve_angle="/theta")


def test_a_broken_or_renamed_bag_and_a_missing_library(tmp_path, monkeypatch):
    good = _simple(tmp_path)
    cut = tmp_path / "cut.bag"
    cut.write_bytes(good.read_bytes()[:200])
    with pytest.raises(ValueError, match=r"cut.bag: cannot read it as a ROS 1 bag \(") as info:
        io.read_log(cut, input="/f")
    assert "\n" not in str(info.value)
    renamed = tmp_path / "run.dat"
    renamed.write_bytes(good.read_bytes())
    with pytest.raises(ValueError, match=r"this is a ROS 1 bag, not a data table.*name it .bag"):
        io.read_log(renamed, input="/f")
    with pytest.raises(ValueError, match=r"data file not found: .*missing.bag"):
        io.read_log(tmp_path / "missing.bag", input="/f")
    monkeypatch.setitem(sys.modules, "rosbags.highlevel", None)
    with pytest.raises(ValueError, match=r"needs the rosbags library: pip install "):
        io.read_log(good, input="/f")


@pytest.mark.parametrize("kind", KINDS)
def test_columns_lists_every_number_as_topic_and_field(tmp_path, kind):
    cols = io.columns(_simple(tmp_path, kind))
    assert "/f" in cols and "/f:data" in cols
    assert {"/js:position[0]", "/js:position[1]", "/js:header.stamp.sec"} <= set(cols)
    assert "/js" not in cols  # more than one number: no bare topic


def test_a_long_array_lists_its_first_items_only(tmp_path):
    topics = {"/big": [(EPOCH_NS, joint_state("ros1", EPOCH_NS, np.arange(5000.0)))]}
    cols = io.columns(_bag(tmp_path, "ros1", topics))
    assert "/big:position[63]" in cols and "/big:position[64]" not in cols
    # 40 fields listed: the ROS 1 header's three numbers, then position[0] to position[36]
    with pytest.raises(
        ValueError, match=r"stamp.nanosec, position\[0\], .*, position\[36\], \.\.\.$"
    ):
        io.read_log(_bag(tmp_path, "ros1", topics, name="b"), input="/big:nope")


def test_constant_curve_angle_and_a_curve_angle_topic(tmp_path):
    ns = EPOCH_NS + np.arange(5) * 10_000_000
    topics = {
        "/x": [(s, float64("ros1", k)) for k, s in enumerate(ns)],
        "/theta": [(s, float64("ros1", 0.5 + k)) for k, s in enumerate(ns)],
    }
    path = _bag(tmp_path, "ros1", topics)
    np.testing.assert_array_equal(io.read_log(path, input="/x", curve_angle=1.5).curve_angle, 1.5)
    log = io.read_log(path, input="/x", curve_angle="/theta")
    np.testing.assert_allclose(log.curve_angle, 0.5 + np.arange(5.0))


@pytest.mark.parametrize("kind", KINDS)
def test_joint_state_fields_selected_by_joint_name_follow_a_reordering(tmp_path, kind):
    """position[bend] is the item at the place of 'bend' in each message's name list: the
    publisher swaps its joints' order every other message, the values stay the bend's."""
    rng = np.random.default_rng(11)
    ns = EPOCH_NS + np.arange(12) * 10_000_000
    bend, roll = rng.normal(size=12), rng.normal(size=12)
    msgs = []
    for k, s in enumerate(ns):
        if k % 2:
            msgs.append((s, joint_state(kind, s, [roll[k], bend[k]], names=["roll", "bend"])))
        else:
            msgs.append((s, joint_state(kind, s, [bend[k], roll[k]], names=["bend", "roll"])))
    path = _bag(tmp_path, kind, {"/joint_states": msgs})
    log = io.read_log(
        path, input="/joint_states:position[bend]", output="/joint_states:position[roll]"
    )
    np.testing.assert_array_equal(log.x, bend)
    np.testing.assert_array_equal(log.y, roll)
    with pytest.raises(
        ValueError,
        match=r"no input field 'position\[pitch\]' \(position\[pitch\] has no name 'pitch'; "
        r"names: 'bend', 'roll'\)",
    ):
        io.read_log(path, input="/joint_states:position[pitch]")
    with pytest.raises(
        ValueError, match=r"\(velocity\[bend\] has 0 item\(s\), none for 'bend' \(name 1\)\)"
    ):
        io.read_log(path, input="/joint_states:velocity[bend]")


def test_a_joint_name_missing_from_a_later_message_names_the_message(tmp_path):
    ns = EPOCH_NS + np.arange(5) * 10_000_000
    names = [["bend", "roll"]] * 3 + [["roll", "wrist"]] + [["bend", "roll"]]
    msgs = [
        (s, joint_state("ros1", s, [1.0, 2.0], names=n)) for s, n in zip(ns, names, strict=True)
    ]
    with pytest.raises(
        ValueError,
        match=r"topic /js, message 4: position\[bend\] has no name 'bend'; "
        r"names: 'roll', 'wrist'$",
    ):
        io.read_log(_bag(tmp_path, "ros1", {"/js": msgs}), input="/js:position[bend]")
    topics = {"/p": [(s, point_stamped("ros1", s, 1.0)) for s in ns]}
    with pytest.raises(ValueError, match=r"cannot be selected by name: no list of names"):
        io.read_log(_bag(tmp_path, "ros1", topics, name="p"), input="/p:point[x]")


@pytest.mark.parametrize("kind", KINDS)
def test_header_stamps_against_receive_times_are_noted_with_the_latency(tmp_path, kind):
    """The input stamped by its header, the output (no header) by its receive time: the
    note names both and the input's median latency (receive - header), 2.5 ms here."""
    stamps = EPOCH_NS + np.arange(20) * 10_000_000
    latency = 2_500_000 + np.arange(20) % 3 * 100_000  # 2.5, 2.6, 2.7 ms: median 2.6
    topics = {
        "/js": [
            (s + d, joint_state(kind, s, [0.1 * k]))
            for k, (s, d) in enumerate(zip(stamps, latency, strict=True))
        ],
        "/tip": [(s + 5_000_000, float64(kind, k)) for k, s in enumerate(stamps)],
    }
    path = _bag(tmp_path, kind, topics)
    log = io.read_log(path, input="/js:position[0]", output="/tip")
    text = " | ".join(log.notes)
    assert (
        "mixed time bases: /js by header stamps (when measured), /tip by the bag's receive "
        "time (when recorded)" in text
    )
    assert f"median receive - header: /js {np.median(latency) * 1e-6:.3g} ms" in text
    alike = io.read_log(path, input="/js:position[0]", output="/tip", time="receive")
    assert not any("mixed time bases" in n for n in alike.notes)
    with pytest.raises(ValueError, match=r"time_unit 'ms' applies to a /topic:field time"):
        io.read_log(path, input="/js:position[0]", output="/tip", time_unit="ms")


def test_a_numeric_time_field_in_a_time_unit(tmp_path):
    ns = EPOCH_NS + np.arange(6) * 10_000_000
    msgs = [(s, joint_state("ros1", s, [k, 4.0 * k])) for k, s in enumerate(ns)]
    path = _bag(tmp_path, "ros1", {"/js": msgs})
    log = io.read_log(path, input="/js:position[0]", time="/js:position[1]", time_unit="ms")
    np.testing.assert_allclose(log.t, 0.004 * np.arange(6), rtol=0, atol=1e-12)
