"""Reading the many ways users write times into one form: int64 nanoseconds.

Relative times (offsets) are ``timedelta64[ns]``; absolute times are ``datetime64[ns]``
(naive, UTC). Accepted inputs:

- float or int seconds, alone or in a sequence or array;
- ``numpy.timedelta64`` / ``numpy.datetime64`` scalars and arrays;
- ``datetime.timedelta`` / ``datetime.datetime`` (time-zone aware ones are converted to UTC);
- strings: plain seconds ``"1.5"``, durations ``"2s"``, ``"500 ms"``, ``"1.5min"``, ISO 8601
  ``"P0DT0H0M4.4S"`` and ``"PT2S"``, and timestamps ``"2024-03-01T08:00:00"`` (``Z`` or
  ``+01:00`` accepted);
- pandas ``Timedelta``, ``TimedeltaIndex``, ``Timestamp``, ``DatetimeIndex`` and ``Series``
  (pandas is optional and never imported here);
- pint quantities of time (``Q_([0, 500], "ms")``), in any time unit;
- a :class:`TimeAxis`, such as ``FrameTree.time_union()`` returns.
"""

from __future__ import annotations

import datetime as _dt
import re
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
from numpy.typing import NDArray

from ..errors import InvalidTimeError
from .quantities import seconds as quantity_seconds

__all__ = [
    "TimeAxis",
    "anchor_time_axis",
    "format_timedelta_iso",
    "format_timestamp_iso",
    "parse_time_axis",
    "parse_timedelta",
    "parse_timestamp",
    "shift_ns",
    "timestamp_ns",
]

_NS_LIMIT = 2**63 - 1
"""Largest int64 nanosecond count (int64 min is NaT): about 292 years."""
_NS_PER_UNIT = {
    "ns": 1, "nanosecond": 1, "nanoseconds": 1,
    "us": 1_000, "µs": 1_000, "microsecond": 1_000, "microseconds": 1_000,
    "ms": 1_000_000, "millisecond": 1_000_000, "milliseconds": 1_000_000,
    "s": 1_000_000_000, "sec": 1_000_000_000, "second": 1_000_000_000,
    "seconds": 1_000_000_000,
    "min": 60_000_000_000, "minute": 60_000_000_000, "minutes": 60_000_000_000,
    "h": 3_600_000_000_000, "hour": 3_600_000_000_000, "hours": 3_600_000_000_000,
    "d": 86_400_000_000_000, "day": 86_400_000_000_000, "days": 86_400_000_000_000,
}
_DURATION = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-zµ]+)\s*$")
_NUMBER = re.compile(r"^[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?$")
_ISO_DURATION = re.compile(
    r"^(?P<sign>[-+])?P(?:(?P<days>[-+]?\d+(?:\.\d+)?)D)?"
    r"(?:T(?:(?P<hours>[-+]?\d+(?:\.\d+)?)H)?(?:(?P<minutes>[-+]?\d+(?:\.\d+)?)M)?"
    r"(?:(?P<seconds>[-+]?\d+(?:\.\d+)?)S)?)?$"
)


@dataclass(frozen=True)
class TimeAxis:
    """Times as int64 nanoseconds.

    Attributes
    ----------
    offsets : ndarray of int64, shape (T,)
        Nanoseconds after ``reference`` (or plain relative offsets when it is None).
    reference : numpy.datetime64 or None
        The timestamp the offsets count from; set for absolute input.
    """

    offsets: NDArray[np.int64]
    reference: np.datetime64 | None

    @property
    def is_absolute(self) -> bool:
        """True when the times are anchored to a reference timestamp."""
        return self.reference is not None

    def as_numpy(self) -> NDArray[np.datetime64] | NDArray[np.timedelta64]:
        """The times as numpy: ``datetime64[ns]`` instants when anchored to a reference,
        else ``timedelta64[ns]`` offsets (what every time argument of pinframes takes)."""
        offsets = self.offsets.astype("timedelta64[ns]")
        return offsets if self.reference is None else self.reference + offsets


def parse_time_axis(values: Any, *, field: str = "times") -> TimeAxis:
    """Read one or many times into a :class:`TimeAxis`.

    Absolute input gets its first value as reference; relative input has no reference.
    Mixing absolute and relative values is an error. A :class:`TimeAxis` (what
    ``FrameTree.time_union`` returns) is taken as it is.
    """
    if isinstance(values, TimeAxis):
        return TimeAxis(np.array(values.offsets, dtype=np.int64).reshape(-1), values.reference)
    if isinstance(values, (float, int)) and not isinstance(values, bool) and abs(values) < 9e9:
        return TimeAxis(np.array([round(values * 1e9)], dtype=np.int64), None)
    array = _as_time_array(values, field)
    if np.isnat(array).any():
        raise InvalidTimeError("not-a-time (NaT) values", field=field)
    if array.dtype.kind == "M":
        reference = array[0]
        return TimeAxis(shift_ns(array.astype(np.int64), -timestamp_ns(reference), field=field),
                        reference)
    return TimeAxis(array.astype(np.int64), None)


def anchor_time_axis(axis: TimeAxis, reference: np.datetime64, *,
                     field: str = "times") -> TimeAxis:
    """``axis`` counted from the timestamp ``reference`` (ns); absolute input keeps its instants.

    Raises :class:`InvalidTimeError` when an offset or an absolute time would leave int64
    nanoseconds (numpy would wrap it around without a word).
    """
    base = timestamp_ns(reference)
    shift = timestamp_ns(axis.reference) - base if axis.reference is not None else 0
    offsets = shift_ns(axis.offsets, shift, field=field)
    shift_ns(offsets, base, field=field)  # the instants must fit as well
    return TimeAxis(offsets, reference)


def shift_ns(nanoseconds: NDArray[np.int64], shift: int, *,
             field: str = "times") -> NDArray[np.int64]:
    """``nanoseconds + shift``, or :class:`InvalidTimeError` where int64 would wrap around."""
    if nanoseconds.size and (int(nanoseconds.min()) + shift < -_NS_LIMIT
                             or int(nanoseconds.max()) + shift > _NS_LIMIT):
        raise _beyond_nanoseconds(field)
    return nanoseconds + np.int64(shift)


def timestamp_ns(timestamp: np.datetime64) -> int:
    """``timestamp`` as nanoseconds since 1970-01-01 (a Python int: no wrap-around)."""
    return int(timestamp.astype("datetime64[ns]").astype(np.int64))


def parse_timestamp(value: Any, *, field: str = "reference_time") -> np.datetime64:
    """Read one absolute time into ``numpy.datetime64[ns]``."""
    array = _as_time_array(value, field)
    if array.dtype.kind != "M" or array.size != 1:
        raise InvalidTimeError(f"expected one timestamp, got {value!r}", field=field)
    stamp = array[0]
    if np.isnat(stamp):
        raise InvalidTimeError("not-a-time (NaT)", field=field)
    return stamp


def parse_timedelta(value: Any, *, field: str = "time") -> np.timedelta64:
    """Read one relative time (duration) into ``numpy.timedelta64[ns]``."""
    axis = parse_time_axis(value, field=field)
    if axis.is_absolute or axis.offsets.size != 1:
        raise InvalidTimeError(f"expected one duration, got {value!r}", field=field)
    return axis.offsets.astype("timedelta64[ns]")[0]


def format_timedelta_iso(nanoseconds: int) -> str:
    """ISO 8601 duration as pandas and weldx write it: ``P0DT0H0M4.4S``, ``P-1DT23H59M59S``."""
    days, rest = divmod(int(nanoseconds), 86_400_000_000_000)
    hours, rest = divmod(rest, 3_600_000_000_000)
    minutes, rest = divmod(rest, 60_000_000_000)
    seconds, fraction = divmod(rest, 1_000_000_000)
    text = f"{seconds}.{fraction:09d}".rstrip("0").rstrip(".") if fraction else str(seconds)
    return f"P{days}DT{hours}H{minutes}M{text}S"


def format_timestamp_iso(stamp: np.datetime64) -> str:
    """ISO 8601 timestamp without zone (naive UTC): ``2024-03-01T08:00:05``, with the
    nanoseconds' trailing zeros dropped when there is a fraction (``2024-03-01T08:00:05.25``)."""
    seconds, fraction = divmod(timestamp_ns(stamp), 1_000_000_000)
    text = str(np.datetime64(seconds, "s"))
    return f"{text}.{fraction:09d}".rstrip("0") if fraction else text


def _as_time_array(values: Any, field: str) -> np.ndarray:
    """``datetime64[ns]`` or ``timedelta64[ns]`` (float seconds become the latter)."""
    values = quantity_seconds(_from_pandas(values), field)
    if isinstance(values, (str, bytes, _dt.datetime, _dt.date, _dt.timedelta, np.generic)):
        values = [values]
    try:
        array = np.asarray(values)
    except (TypeError, ValueError) as exc:
        raise InvalidTimeError(f"cannot read times from {values!r}: {exc}", field=field) from None
    if array.ndim == 0:
        array = array.reshape(1)
    if array.ndim != 1:
        raise InvalidTimeError(f"expected a 1-D sequence of times, got shape {array.shape}",
                               field=field)
    if array.size == 0:
        raise InvalidTimeError("no times given", field=field)
    if array.dtype.kind in "mM":
        return _in_nanoseconds(array, field)
    if array.dtype.kind in "iuf":
        seconds = array.astype(float)
        if not np.all(np.isfinite(seconds)):
            raise InvalidTimeError("times must be finite numbers of seconds", field=field)
        if np.max(np.abs(seconds)) > _NS_LIMIT / 1e9:
            raise _beyond_nanoseconds(field)
        return np.round(seconds * 1e9).astype(np.int64).astype("timedelta64[ns]")
    items = list(values) if isinstance(values, (list, tuple)) else array.tolist()
    return _parse_elements(items, values, field)


def _parse_elements(items: list[Any], original: Any, field: str) -> np.ndarray:
    parsed = [_parse_one(item, field) for item in items]
    kinds = {value.dtype.kind for value in parsed}
    if len(kinds) > 1:
        raise InvalidTimeError(
            f"mixes absolute timestamps and relative durations: {original!r}", field=field
        )
    unit = "datetime64[ns]" if kinds == {"M"} else "timedelta64[ns]"
    return np.array([_in_nanoseconds(np.array([value]), field)[0] for value in parsed],
                    dtype=unit)


def _parse_one(item: Any, field: str) -> np.generic:
    if isinstance(item, np.generic) and item.dtype.kind in "mM":
        return item
    if isinstance(item, _dt.date) and item != item:  # pandas.NaT is a datetime unequal to itself
        raise InvalidTimeError("not-a-time (NaT) values", field=field)
    if isinstance(item, _dt.datetime):
        if item.tzinfo is not None:
            item = item.astimezone(_dt.timezone.utc).replace(tzinfo=None)
        return np.datetime64(item)
    if isinstance(item, _dt.date):
        return np.datetime64(item)
    if isinstance(item, _dt.timedelta):
        return np.timedelta64(item)
    if isinstance(item, (int, float, np.integer, np.floating)) and not isinstance(item, bool):
        try:
            seconds = float(item)
        except OverflowError:
            raise _beyond_nanoseconds(field) from None
        if not np.isfinite(seconds):
            raise InvalidTimeError("times must be finite numbers of seconds", field=field)
        return _duration(seconds * 1e9, field)
    if isinstance(item, bytes):
        item = item.decode("utf-8", "replace")
    if isinstance(item, str):
        return _parse_string(item, field)
    raise InvalidTimeError(f"cannot read a time from {item!r}", field=field)


def _parse_string(text: str, field: str) -> np.generic:
    duration = _parse_duration_string(text.strip())
    if duration is not None:
        return _duration(duration, field)
    return _parse_timestamp_string(text.strip(), field)


def _parse_duration_string(text: str) -> float | int | None:
    """Nanoseconds of a duration string (may be huge or infinite), None if it is none."""
    if _NUMBER.match(text):
        return float(text) * _NS_PER_UNIT["s"]
    match = _DURATION.match(text)
    if match and match.group(2) in _NS_PER_UNIT:
        return float(match.group(1)) * _NS_PER_UNIT[match.group(2)]
    match = _ISO_DURATION.match(text)
    if match and text not in ("P", "PT") and not text.endswith("T"):
        parts = match.groupdict()
        total = 0.0
        nanoseconds = 0
        for name, unit in (("days", "d"), ("hours", "h"), ("minutes", "min")):
            if parts[name]:
                total += float(parts[name]) * _NS_PER_UNIT[unit]
        if parts["seconds"]:
            nanoseconds = _seconds_text_to_ns(parts["seconds"])
        value = (round(total) if np.isfinite(total) else total) + nanoseconds
        return -value if parts["sign"] == "-" else value
    return None


def _seconds_text_to_ns(text: str) -> int:
    """Exact nanoseconds of a decimal seconds string such as ``-4.400000001``."""
    sign = -1 if text.startswith("-") else 1
    whole, _, fraction = text.lstrip("+-").partition(".")
    return sign * (int(whole or 0) * 1_000_000_000 + int((fraction + "000000000")[:9]))


def _parse_timestamp_string(text: str, field: str) -> np.datetime64:
    has_zone = text.endswith(("Z", "z")) or re.search(r"[+-]\d\d:?\d\d$", text[10:]) is not None
    if has_zone:
        try:
            stamp = _dt.datetime.fromisoformat(text.replace("z", "+00:00").replace("Z", "+00:00"))
        except ValueError:
            raise InvalidTimeError(f"cannot read a time from {text!r}", field=field) from None
        return cast(np.datetime64, _parse_one(stamp, field))
    try:
        return cast(np.datetime64, np.datetime64(text))
    except ValueError:
        raise InvalidTimeError(
            f"cannot read a time from {text!r} (expected seconds, a duration such as '2s' "
            "or 'P0DT0H0M2S', or a timestamp such as '2024-03-01T08:00:00')",
            field=field,
        ) from None


def _duration(nanoseconds: float | int, field: str) -> np.timedelta64:
    """``timedelta64[ns]`` of a (possibly huge or infinite) number of nanoseconds."""
    if not abs(nanoseconds) <= _NS_LIMIT:
        raise _beyond_nanoseconds(field)
    return np.timedelta64(round(nanoseconds), "ns")


def _in_nanoseconds(array: np.ndarray, field: str) -> np.ndarray:
    """A ``datetime64`` or ``timedelta64`` array of any unit in nanoseconds.

    numpy wraps values that do not fit in int64 nanoseconds around without a word
    (``9999-12-31`` becomes ``1816-03-29``), so the range is checked in the array's own unit.
    """
    kind = "datetime64" if array.dtype.kind == "M" else "timedelta64"
    unit, _ = np.datetime_data(array.dtype)
    if kind == "timedelta64" and unit in ("Y", "M"):  # numpy would take an average length
        raise InvalidTimeError(f"durations in {'years' if unit == 'Y' else 'months'} have no "
                               "fixed length; give them in days or smaller units", field=field)
    if unit not in ("ns", "ps", "fs", "as", "generic"):
        values = array.astype(np.int64)
        values = values[values != np.iinfo(np.int64).min]  # NaT, reported by the callers
        limit = np.datetime64(_NS_LIMIT, "ns").astype(f"datetime64[{unit}]").astype(np.int64)
        if values.size and np.max(np.abs(values)) > limit:
            raise _beyond_nanoseconds(field)
    try:
        return array.astype(f"{kind}[ns]")
    except TypeError as exc:  # timedelta64 in months or years: no fixed length
        raise InvalidTimeError(f"cannot read times in {array.dtype}: {exc}", field=field) from None


def _beyond_nanoseconds(field: str) -> InvalidTimeError:
    return InvalidTimeError(
        "times beyond +-292 years (of 1970 for timestamps) do not fit in int64 nanoseconds",
        field=field)


def _from_pandas(values: Any) -> Any:
    """Turn pandas time objects into numpy ones without importing pandas."""
    module = type(values).__module__
    if not module.startswith("pandas"):
        return values
    if getattr(values, "tz", None) is not None:
        values = values.tz_convert("UTC").tz_localize(None)
    for converter in ("to_datetime64", "to_timedelta64", "to_numpy"):
        if hasattr(values, converter):
            return getattr(values, converter)()
    return values
