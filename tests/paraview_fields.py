"""Run by ParaView's pvbatch for tests/test_paraview_and_history.py: opens each XDMF index given with each of
ParaView's XDMF readers (the legacy XDMFReader and the Xdmf3 readers), reads every snapshot, and
saves every point and cell array each reader gives, with its components, to an .npz file:
    pvbatch tests/paraview_fields.py OUT.npz A/solution.xmf [B/solution.xmf ...]
Keys are "FILE_INDEX/READER/SNAPSHOT/point|cell/NAME", and "FILE_INDEX/READER/SNAPSHOT/time".
No rendering: the readers' output is fetched to the client, so no display or GPU is needed."""
import sys

import numpy as np
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy

READERS = {"XDMFReader": "FileNames", "Xdmf3ReaderS": "FileName", "Xdmf3ReaderT": "FileName"}

out, files = sys.argv[1], sys.argv[2:]
arrays = {}
for i, xmf in enumerate(files):
    for reader, prop in READERS.items():
        r = getattr(simple, reader)(**{prop: [xmf]})
        tv = r.TimestepValues
        times = list(tv) if hasattr(tv, "__len__") else [tv]  # one snapshot: a number, not a list
        for k, t in enumerate(times):
            r.UpdatePipeline(t)
            d = servermanager.Fetch(r)
            arrays[f"{i}/{reader}/{k}/time"] = np.array(t)
            for assoc, data in (("point", d.GetPointData()), ("cell", d.GetCellData())):
                for j in range(data.GetNumberOfArrays()):
                    a = data.GetArray(j)
                    arrays[f"{i}/{reader}/{k}/{assoc}/{a.GetName()}"] = vtk_to_numpy(a).copy()  # the reader may free or reuse its memory at the next snapshot
        simple.Delete(r)
np.savez(out, **arrays)
