# fc_check.py -- run by scripts/freecad_check.sh through freecadcmd (which does not forward argv:
# the file comes in FC_FILE). Reads a STEP or IGES file with FreeCAD's Part module and prints one
# line: faces, edges, shells, edges shared by two faces, free edges, validity, area, the largest
# distance of 5 x 5 surface points per face from the torus R = 3, r = 1 (relative to R + r; when
# FC_TORUS is set), the triangles of a FreeCAD mesh of the shape, how many free edges are
# degenerate (zero length, at a pole) and whether every shell is closed.
import math
import os
from collections import Counter

import Part

path = os.environ["FC_FILE"]
s = Part.Shape()
s.read(path)
uses = Counter()
for f in s.Faces:
    for e in f.Edges:
        uses[e.hashCode()] += 1
shared = sum(1 for v in uses.values() if v == 2)
free = sum(1 for v in uses.values() if v == 1)
# a capped end's fan faces each have a zero-length edge at the pole, used by that face alone
degenerate = sum(1 for f in s.Faces for e in f.Edges if uses[e.hashCode()] == 1 and e.Degenerated)
closed = int(len(s.Shells) > 0 and all(sh.isClosed() for sh in s.Shells))
worst = 0.0
if os.environ.get("FC_TORUS"):
    for f in s.Faces:
        u0, u1, v0, v1 = f.ParameterRange
        for i in range(5):
            for j in range(5):
                p = f.Surface.value(u0 + (u1 - u0) * i / 4, v0 + (v1 - v0) * j / 4)
                worst = max(worst, abs(math.hypot(math.hypot(p.x, p.y) - 3, p.z) - 1) / 4)
try:
    import MeshPart
    triangles = MeshPart.meshFromShape(Shape=s, LinearDeflection=0.05).CountFacets
except Exception:
    triangles = -1
print("FC file=%s faces=%d edges=%d shells=%d shared=%d free=%d valid=%d area=%.12g torus_dev=%.3g triangles=%d"
      " degenerate=%d closed=%d"
      % (os.path.basename(path), len(s.Faces), len(s.Edges), len(s.Shells), shared, free, int(s.isValid()),
         s.Area, worst, triangles, degenerate, closed))
