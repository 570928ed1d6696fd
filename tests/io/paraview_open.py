"""Open a FieldWriter XDMF with ParaView's reader and check what ParaView sees.

Usage: pvpython paraview_open.py results.xdmf   (written by test_field_writer, two_steps)
Checks: two time steps, 3 points, the fields, and that the stress tensor's components reach
ParaView in the right places (the file keeps Voigt order, XDMF's Tensor6 another).
"""
import sys

from paraview import servermanager
from paraview.simple import XDMFReader

reader = XDMFReader(FileNames=[sys.argv[1]])
times = list(reader.TimestepValues)
assert times == [0.0, 0.375], times
reader.UpdatePipeline(0.375)
data = servermanager.Fetch(reader)
assert data.GetNumberOfPoints() == 3, data.GetNumberOfPoints()
pd = data.GetPointData()
names = sorted(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays()))
assert names == ["material", "stress"], names
stress = pd.GetArray("stress")
assert stress.GetNumberOfComponents() == 9, stress.GetNumberOfComponents()
# Second point: Voigt (xx yy zz xy xz yz) = (7 8 9 10 11 12); ParaView holds the full 3x3 row-major.
full = [stress.GetComponent(1, c) for c in range(9)]
assert full == [7, 10, 11, 10, 8, 12, 11, 12, 9], full
x = data.GetPoint(1)
assert tuple(x) == (2.5, 3.0, 0.0), x
print("ParaView reads", len(times), "steps, fields", names, "stress row", full[:3])
