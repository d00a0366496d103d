import datetime as dt

import numpy as np
import pytest

from pinframes.errors import InvalidTimeError
from pinframes.values.timeconv import (
    TimeAxis,
    format_timedelta_iso,
    format_timestamp_iso,
    parse_time_axis,
    parse_timedelta,
    parse_timestamp,
)

SECOND = 1_000_000_000


@pytest.mark.parametrize(
    ("value", "expected_ns"),
    [
        (2.5, [2_500_000_000]),
        ([0, 1, 2], [0, SECOND, 2 * SECOND]),
        ("2s", [2 * SECOND]),
        ("500 ms", [500_000_000]),
        ("1.5min", [90 * SECOND]),
        ("P0DT0H0M4.4S", [4_400_000_000]),
        ("PT2S", [2 * SECOND]),
        ("P-1DT23H59M59S", [-SECOND]),
        ("P0DT0H0M0.000000001S", [1]),
        (np.timedelta64(3, "ms"), [3_000_000]),
        (np.array([1, 2], dtype="timedelta64[s]"), [SECOND, 2 * SECOND]),
        (dt.timedelta(minutes=1), [60 * SECOND]),
    ],
)
def test_relative_times(value, expected_ns):
    axis = parse_time_axis(value)
    assert axis.reference is None
    assert axis.offsets.tolist() == expected_ns


def test_absolute_times_take_their_first_value_as_reference():
    axis = parse_time_axis(["2024-03-01T08:00:00", "2024-03-01T08:00:01.5"])
    assert axis.reference == np.datetime64("2024-03-01T08:00:00", "ns")
    assert axis.offsets.tolist() == [0, 1_500_000_000]


def test_time_zones_are_converted_to_utc():
    assert parse_timestamp("2024-03-01T09:00:00+01:00") == np.datetime64("2024-03-01T08:00")
    assert parse_timestamp("2024-03-01T08:00:00Z") == np.datetime64("2024-03-01T08:00")
    aware = dt.datetime(2024, 3, 1, 10, tzinfo=dt.timezone(dt.timedelta(hours=2)))
    assert parse_timestamp(aware) == np.datetime64("2024-03-01T08:00")


def test_pandas_objects_when_pandas_is_installed():
    pd = pytest.importorskip("pandas")
    assert parse_time_axis(pd.to_timedelta([0, 1], unit="s")).offsets.tolist() == [0, SECOND]
    index = pd.date_range("2024-01-01", periods=3, freq="500ms", tz="Europe/Berlin")
    axis = parse_time_axis(index)
    assert axis.reference == np.datetime64("2023-12-31T23:00:00", "ns")
    assert axis.offsets.tolist() == [0, 500_000_000, SECOND]
    assert parse_timestamp(pd.Timestamp("2024-01-01 12:00")) == np.datetime64("2024-01-01T12:00")
    assert parse_timedelta(pd.Timedelta("3s")) == np.timedelta64(3, "s")


@pytest.mark.parametrize(
    "bad", ["yesterday", [1, "2024-01-01"], float("nan"), [[1, 2]], [], None, "P", object()]
)
def test_bad_times_raise_invalid_time_error(bad):
    with pytest.raises(InvalidTimeError):
        parse_time_axis(bad)


def test_iso_duration_formatting_round_trips():
    for ns in [0, 1, 4_400_000_000, -SECOND, 86_400 * SECOND + 3, -123_456_789_012]:
        text = format_timedelta_iso(ns)
        assert text.startswith("P")
        assert parse_time_axis(text).offsets[0] == ns
    assert format_timedelta_iso(-SECOND) == "P-1DT23H59M59S"
    assert format_timedelta_iso(4_400_000_000) == "P0DT0H0M4.4S"


@pytest.mark.parametrize(("stamp", "text"), [
    ("2024-03-01T08:00:05", "2024-03-01T08:00:05"),
    ("2024-03-01T08:00:05.250", "2024-03-01T08:00:05.25"),
    ("2024-03-01T08:00:05.000000001", "2024-03-01T08:00:05.000000001"),
    ("1969-12-31T23:59:59.5", "1969-12-31T23:59:59.5"),  # before 1970: floor division
])
def test_iso_timestamp_formatting(stamp, text):
    assert format_timestamp_iso(np.datetime64(stamp, "ns")) == text
    assert parse_timestamp(text) == np.datetime64(stamp, "ns")


def test_plain_number_strings_are_seconds():
    assert parse_time_axis(["0", "1.5"]).offsets.tolist() == [0, 1_500_000_000]


def test_time_axis_as_numpy():
    relative = TimeAxis(np.array([0, 1_500_000_000]), None)
    np.testing.assert_array_equal(relative.as_numpy(),
                                  np.array([0, 1_500_000_000], dtype="timedelta64[ns]"))
    anchored = TimeAxis(np.array([0, 2]), np.datetime64("2026-01-01T00:00:00", "ns"))
    np.testing.assert_array_equal(anchored.as_numpy(), np.array(
        ["2026-01-01T00:00:00.000000000", "2026-01-01T00:00:00.000000002"],
        dtype="datetime64[ns]"))
    assert anchored.as_numpy().dtype == np.dtype("datetime64[ns]")
