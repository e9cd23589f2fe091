"""Opens an XDMF index the way a ParaView user does and reports what ParaView sees.

Run with ParaView's own interpreter under a virtual display:
    xvfb-run -a pvpython tests/python/paraview_check.py particles.xmf view.png

It opens the file with the reader ParaView picks for it (OpenDataFile), and prints
one JSON object: the reader, the time steps and, per time step, the number of points
and cells and the range of every point field. It then shows the last time step in a
render view with the default representation, coloured by pressure, and saves it as
a PNG, the picture a user gets after File > Open > Apply. Any file ParaView opens
will do: the free-surface collection (surface.pvd) is coloured by its first field.
"""

import json
import sys

from paraview import servermanager
from paraview.simple import (
    ColorBy,
    CreateView,
    GetDisplayProperties,
    OpenDataFile,
    Render,
    SaveScreenshot,
    Show,
)


def describe(data):
    fields = {}
    points = data.GetPointData()
    for k in range(points.GetNumberOfArrays()):
        array = points.GetArray(k)
        fields[array.GetName()] = {
            "components": array.GetNumberOfComponents(),
            "range": list(array.GetRange(-1 if array.GetNumberOfComponents() > 1 else 0)),
            "first": [array.GetComponent(0, c) for c in range(array.GetNumberOfComponents())],
        }
    return {
        "points": data.GetNumberOfPoints(),
        "cells": data.GetNumberOfCells(),
        "fields": fields,
    }


def main(index, png):
    reader = OpenDataFile(index)
    values = reader.TimestepValues
    times = [float(values)] if isinstance(values, (int, float)) else list(values) or [0.0]
    steps = []
    for t in times:
        reader.UpdatePipeline(t)
        steps.append(describe(servermanager.Fetch(reader)))
    view = CreateView("RenderView")
    view.ViewSize = [640, 400]
    view.OrientationAxesVisibility = 0
    view.ViewTime = times[-1]
    Show(reader, view)
    display = GetDisplayProperties(reader, view)
    # the particles by pressure; a mesh (the free surface) by its first field
    fields = list(steps[-1]["fields"])
    ColorBy(display, ("POINTS", "pressure" if "pressure" in fields else fields[0]))
    view.ResetCamera()
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[640, 400])
    print(json.dumps({
        "reader": reader.GetXMLName(),
        "representation": str(display.Representation).strip("'\""),
        "times": times,
        "steps": steps,
    }))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
