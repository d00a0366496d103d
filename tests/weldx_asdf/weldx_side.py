"""Runs inside a separate environment that has weldx 0.8.2 (never imports pinframes).

Reads one JSON request on stdin, answers one JSON object on stdout. Lengths in the answers
are metres, times are int64 nanoseconds relative to the answer's ``reference_time`` (ISO
string or null), rotations are (3, 3) matrices. Requests (``op``):

- ``hierarchy``: ``{path}`` -> ``{name, root, parents: {frame: parent}, reference_time}``.
- ``get_cs``: ``{path, frame, relative_to, times_ns (or null), time_ref (ISO or null)}`` ->
  ``{translation, rotation, times_ns, reference_time}``; times as timedeltas when no
  ``time_ref`` is given.
- ``get_cs_many``: ``{path, queries: [get_cs requests without path]}`` -> ``{answers: [...]}``,
  one answer per query in order, each as for ``get_cs`` or ``{error: message}`` where weldx
  raised.
- ``write``: ``{path, name, root, reference_time, frames: [{name, parent, translation_m,
  rotation, times_ns, reference_time}]}``: builds the hierarchy with weldx's API and writes it
  under the key ``hierarchy`` (weldx's own writer). With ``data: [{name, frame, points_m,
  triangles, attributes, times_ns, reference_time, bare}]`` it also attaches data (a
  ``SpatialData``, or with ``bare`` the points alone), in millimetres.
- ``get_data_many``: ``{path, queries: [{name, relative_to}]}`` -> ``{answers: [{points_m,
  times_ns, reference_time} or {error}]}``: weldx's ``get_data`` in metres; ``times_ns`` as
  int64 nanoseconds after ``reference_time`` when the answer has a time axis.
"""

import json
import sys

import numpy as np
import pandas as pd
import weldx
from weldx import Q_, CoordinateSystemManager, LocalCoordinateSystem, SpatialData, WeldxFile


def _hierarchy_in(path):
    with WeldxFile(path, mode="r") as file:
        found = [value for value in file.values()
                 if isinstance(value, CoordinateSystemManager)]
    if len(found) != 1:
        raise SystemExit(f"{path}: expected one hierarchy, found {len(found)}")
    return found[0]


def _timestamp(value):
    return None if value is None else pd.Timestamp(value)


def _answer_pose(lcs):
    coordinates = lcs.coordinates.data
    translation = np.asarray(coordinates.to("m").m, dtype=float)
    times = None
    if lcs.time is not None:  # one time comes back as a scalar Timedelta
        times = pd.TimedeltaIndex(np.atleast_1d(lcs.time.as_timedelta())).asi8.tolist()
    reference = lcs.reference_time
    return {"translation": translation.tolist(),
            "rotation": np.asarray(lcs.orientation.data, dtype=float).tolist(),
            "times_ns": times,
            "reference_time": None if reference is None else reference.isoformat()}


def hierarchy(request):
    csm = _hierarchy_in(request["path"])
    parents = {name: csm.get_parent_system_name(name) for name in csm.coordinate_system_names
               if name != csm.root_system_name}
    reference = csm.reference_time
    return {"name": csm.name, "root": csm.root_system_name, "parents": parents,
            "reference_time": None if reference is None else reference.isoformat()}


def get_cs(request):
    return _get_cs_in(_hierarchy_in(request["path"]), request)


def get_cs_many(request):
    csm = _hierarchy_in(request["path"])
    answers = []
    for query in request["queries"]:
        try:
            answers.append(_get_cs_in(csm, query))
        except Exception as exc:  # reported back to the test
            answers.append({"error": f"{type(exc).__name__}: {exc}"})
    return {"answers": answers}


def _get_cs_in(csm, request):
    time = None
    if request.get("times_ns") is not None:
        time = pd.to_timedelta(np.asarray(request["times_ns"], dtype=np.int64), unit="ns")
    lcs = csm.get_cs(request["frame"], request["relative_to"], time=time,
                     time_ref=_timestamp(request.get("time_ref")))
    return _answer_pose(lcs)


def write(request):
    csm = CoordinateSystemManager(request["root"], request["name"],
                                  time_ref=_timestamp(request.get("reference_time")))
    for frame in request["frames"]:
        times = frame.get("times_ns")
        lcs = LocalCoordinateSystem(
            orientation=np.asarray(frame["rotation"], dtype=float),
            coordinates=Q_(np.asarray(frame["translation_m"], dtype=float), "m"),
            time=None if times is None else pd.to_timedelta(np.asarray(times, np.int64),
                                                             unit="ns"),
            time_ref=_timestamp(frame.get("reference_time")))
        csm.add_cs(frame["name"], frame["parent"], lcs)
    for data in request.get("data", []):
        csm.assign_data(_spatial_data(data), data["name"], data["frame"])
    with WeldxFile(request["path"], mode="rw", tree={"hierarchy": csm}):
        pass
    return {"weldx": weldx.__version__}


def _spatial_data(data):
    points = Q_(np.asarray(data["points_m"], dtype=float) * 1000.0, "mm")
    if data.get("bare"):
        return points
    time = None
    if data.get("times_ns") is not None:
        time = pd.to_timedelta(np.asarray(data["times_ns"], np.int64), unit="ns")
        if data.get("reference_time") is not None:
            time = pd.Timestamp(data["reference_time"]) + time
    attributes = {key: np.asarray(value) for key, value in (data.get("attributes") or {}).items()}
    return SpatialData(points, triangles=data.get("triangles"), attributes=attributes or None,
                       time=time)


def get_data_many(request):
    csm = _hierarchy_in(request["path"])
    answers = []
    for query in request["queries"]:
        try:
            answers.append(_answer_data(csm.get_data(query["name"], query["relative_to"])))
        except Exception as exc:  # reported back to the test
            answers.append({"error": f"{type(exc).__name__}: {exc}"})
    return {"answers": answers}


def _answer_data(data):
    array = data.coordinates if isinstance(data, SpatialData) else data
    array = array.transpose(*(["time"] if "time" in array.dims else []), ..., "c")
    points = np.asarray(array.data.to("m").m, dtype=float)
    times = reference = None
    if "time" in array.coords:
        values = array.coords["time"].values
        if np.issubdtype(values.dtype, np.datetime64):
            reference = pd.Timestamp(values[0])
            values = values - values[0]
        times = values.astype("timedelta64[ns]").astype(np.int64).tolist()
    return {"points_m": points.tolist(), "times_ns": times,
            "reference_time": None if reference is None else reference.isoformat()}


if __name__ == "__main__":
    request = json.load(sys.stdin)
    json.dump({"hierarchy": hierarchy, "get_cs": get_cs, "get_cs_many": get_cs_many,
               "write": write, "get_data_many": get_data_many}[request["op"]](request),
              sys.stdout)
