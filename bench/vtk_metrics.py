#!/usr/bin/python3
"""The VTK baseline of scripts/bench (issue 20): VTK's vtkMeshQuality, the
20 hex metrics VTK 9.1 offers, one filter execution each (VTK computes one
metric per pass), on a mesh already in memory (read from an uncompressed
annotated.vtu, outside the timing). Prints the median over RUNS of the
20 passes' total wall time, in seconds, as JSON on standard output.

usage: vtk_metrics.py ANNOTATED.vtu [RUNS]
"""
import json
import statistics
import sys
import time

from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

HEX_METRICS = ["EdgeRatio", "MedAspectFrobenius", "MaxAspectFrobenius", "MaxEdgeRatios", "Skew", "Taper", "Volume",
               "Stretch", "Diagonal", "Dimension", "Oddy", "Condition", "Jacobian", "ScaledJacobian", "Shear",
               "Shape", "RelativeSizeSquared", "ShapeAndSize", "ShearAndSize", "Distortion"]


def main():
    path, runs = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 3
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        for name in HEX_METRICS:
            q = vtkMeshQuality()
            q.SetInputData(grid)
            getattr(q, "SetHexQualityMeasureTo" + name)()
            q.Update()
        times.append(time.perf_counter() - start)
    json.dump({"cells": grid.GetNumberOfCells(), "metrics": len(HEX_METRICS), "runs_s": times,
               "median_s": statistics.median(times)}, sys.stdout)


if __name__ == "__main__":
    main()
