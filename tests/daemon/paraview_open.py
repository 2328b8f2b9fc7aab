"""Opens a result sidecar the way a ParaView user does ("XDMF Reader") and
reads its first and last frame: usage  pvpython paraview_open.py RESULT_XMF

Exit 0 when the first and last frame the sidecar lists are readable through
it, with every attribute it names present as a point array (read from the
HDF5 file by ParaView's own, non-SWMR, open) and finite; 1 otherwise.  Needs ParaView's pvpython
(Debian: python3-paraview); tests that use it skip when it is missing.
"""
import math
import sys
import xml.etree.ElementTree as ET

from paraview.simple import XDMFReader, servermanager


def main(xmf):
    reader = XDMFReader(FileNames=[xmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    if not times:
        print("FAIL: no frames")
        return 1
    grid = next(g for g in ET.parse(xmf).getroot().iter("Grid") if g.get("GridType") == "Uniform")
    wanted = {a.get("Name") for a in grid.iter("Attribute")}
    ok = True
    for t in (times[0], times[-1]):
        reader.UpdatePipeline(time=t)
        data = servermanager.Fetch(reader)
        pd = data.GetPointData()
        names = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())]
        bad = [n for n in names if not all(math.isfinite(x) for x in pd.GetArray(n).GetRange(-1))]
        missing = sorted(wanted - set(names))
        print("frame at t = %g: %d points, %d of %d arrays%s%s" % (
            t, data.GetNumberOfPoints(), len(names), len(wanted),
            ", missing: %s" % missing if missing else "", ", non-finite: %s" % bad if bad else ""))
        ok = ok and data.GetNumberOfPoints() > 0 and not missing and not bad
    print("%d frames" % len(times))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
