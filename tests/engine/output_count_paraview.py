"""Opens a result sidecar whose frames have different particle counts with
ParaView's "XDMF Reader" and reads every frame:
usage  pvbatch output_count_paraview.py RESULT_XMF COUNT0 COUNT1 ...

Prints each frame's time, number of points and the range of `mass`; exit 0
when every frame has its expected count of points and a finite, positive
mass range, 1 otherwise (tests/engine/output_count_check.py runs it)."""
import math
import sys

from paraview.simple import XDMFReader, servermanager


def main(xmf, counts):
    reader = XDMFReader(FileNames=[xmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    ok = len(times) == len(counts)
    print("paraview: %d frames (expected %d)" % (len(times), len(counts)))
    for k, t in enumerate(times):
        reader.UpdatePipeline(time=t)
        data = servermanager.Fetch(reader)
        arr = data.GetPointData().GetArray("mass")
        lo, hi = arr.GetRange() if arr else (float("nan"), float("nan"))
        n = data.GetNumberOfPoints()
        want = counts[k] if k < len(counts) else -1
        good = n == want and math.isfinite(lo) and math.isfinite(hi) and lo > 0
        print("paraview frame %d t = %.6g: %d points (expected %d), mass %.6g .. %.6g kg%s" % (
            k, t, n, want, lo, hi, "" if good else "  <- wrong"))
        ok = ok and good
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], [int(c) for c in sys.argv[2:]]))
