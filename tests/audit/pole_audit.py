#!/usr/bin/env python3
"""pole_audit.py -- random pole designs through every STEP and IGES layout, the written doubles
against the rule of docs/export.md ("A pole is one point in the file"), sharing no code with the
library.

Each design (design-format.md) is made from a seed: polar spheres, ellipsoids, paraboloids and
two-sheeted hyperboloids capped at one end or both (bi-3 or general caps), Moebius-moved (by b or
by two poles), their poles moved or given a weight, a point of the row next to a pole moved, a
morph of the mesh and its edit, a transform; capped cylinders, cones and transposed torus and
cyclide pieces; Fig. 10's capsule; cones and paraboloids through their apex at the start, the
end or inside the v range, reversed, transposed (the pole along u); clamped NURBS whose first or
last row or column is one point (with weights), or one point but one moved off by 1e-17 to 1e-10
of the size (a short side); placed with scales 1e-6 .. 1e6, rotations and offsets up to 1e5;
one to three parts a design, each an output surface (a polar part sometimes its band too).
`rg2 build` writes the patch dump and STEP and IGES face per patch, IGES B-rep per patch, STEP
and IGES face per mesh and IGES B-rep per mesh. From the dump
alone the audit finds the sides collapsed by the 1e-11 rule, their vertices (closing seams and
collapsed sides merge corners) and each vertex's points; a vertex is a pole when all of them
lie within 16 roundings (DBL_EPSILON times the surface's largest coordinate) times their
weights' ratio (the largest |w| over the smallest, at least 1) of the point h / w of its corner
of lowest index. Then, in every file: every control point of a pole is that point
bit for bit, every other one the correctly rounded h / w of the dump's 4-tuple (per mesh: of the
first patch holding it); every weight the dump's (IGES: times one power of two per entity) and
> 0; neighbouring patches' shared rows the same doubles; every vertex point and edge-curve pole
one of the faces' control points; STEP and IGES of one layout the same points. A design rg2
refuses is skipped (at most a fifth of them may be).

Usage: pole_audit.py RG2 [N [FIRST_SEED]]   (default 120 designs from seed 1)
Prints the figures: poles, their largest spread in roundings, the short sides kept and their
smallest spread (in roundings times their weights' ratio). Exit 0 when every file follows the rule, 1 otherwise, 2 on a usage error.
"""
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile
from fractions import Fraction

class G:
    def __init__(self, rnd):
        self.r = rnd
        self.shapes = {}
        self.meshes = {}
        self.outputs = []
        self.tags = []
        self.n = 0

    def name(self, p):
        self.n += 1
        return "%s%d" % (p, self.n)

    # ---------------------------------------------------------------- placement
    def placement(self):
        r = self.r
        pl = {}
        kind = r.random()
        s = 10 ** r.uniform(-6, 6) if r.random() < 0.6 else 1.0
        if r.random() < 0.2:
            pl["scale"] = [s * r.uniform(0.5, 2), s * r.uniform(0.5, 2), s * r.uniform(0.5, 2)]
        elif s != 1.0:
            pl["scale"] = s
        if r.random() < 0.7:
            rots = []
            for _ in range(r.randint(1, 2)):
                ax = [r.uniform(-1, 1) for _ in range(3)]
                if max(abs(a) for a in ax) < 0.1:
                    ax = [0, 0, 1]
                deg = r.choice([r.uniform(-179, 179), 90.0, 180.0, -90.0, 45.0, 33.0])
                rots.append({"axis": ax, "degrees": deg})
            pl["rotate"] = rots if len(rots) > 1 else rots[0]
        if kind < 0.25:
            off = 1e5 * r.choice([1, -1, 0.3])
            pl["translate"] = [off * r.uniform(-1, 1), off * r.uniform(-1, 1), off]
            self.tags.append("far")
        elif kind < 0.7:
            m = s * 10 ** r.uniform(-1, 5)
            pl["translate"] = [m * r.uniform(-1, 1) for _ in range(3)]
        return pl

    def size_of(self, pl):
        s = pl.get("scale", 1.0)
        if isinstance(s, list):
            s = max(s)
        return s

    # ---------------------------------------------------------------- partitions
    def arcs(self):
        r = self.r
        if r.random() < 0.6:
            return {"arcs": r.randint(3, 12), "from": r.choice([0, 0, r.uniform(0, 360)])}
        n = r.randint(4, 9)
        w = [r.uniform(0.6, 1.4) for _ in range(n)]
        a = [x * 360.0 / sum(w) for x in w]
        if max(a) >= 170:
            return {"arcs": n}
        a[-1] = 360.0 - sum(a[:-1])
        return {"arcs": a, "closed": True}

    def knots01(self, m):
        r = self.r
        k = sorted(r.uniform(0.05, 0.95) for _ in range(m))
        for i in range(1, m):
            if k[i] - k[i - 1] < 0.04:
                return [0.1 + 0.8 * i / (m - 1) for i in range(m)]
        return k

    # ---------------------------------------------------------------- templates
    def polar(self):
        """a polar quadric, maybe Moebius-moved, pole-edited, near-pole-edited, morphed, moved, capped"""
        r = self.r
        kind = r.choice(["sphere", "sphere", "ellipsoid", "paraboloid", "hyperboloid2"])
        lab = self.name("s")
        pl = self.placement()
        sh = {"kind": kind}
        if kind == "sphere":
            sh["radius"] = r.uniform(0.3, 3)
        elif kind == "ellipsoid":
            sh.update(a=r.uniform(0.5, 3), b=r.uniform(0.5, 3), c=r.uniform(0.5, 3))
        elif kind == "paraboloid":
            sh.update(A=r.uniform(0.5, 2), B=r.uniform(0.5, 2))
        else:
            sh.update(a=r.uniform(0.5, 2), c=r.uniform(0.5, 2))
        sh.update(pl)
        self.shapes[lab] = sh
        m = r.randint(2, 6)
        if kind in ("sphere", "ellipsoid"):
            kn = self.knots01(m)
        elif kind == "paraboloid":
            kn = [0.25 * (i + 1) * r.uniform(0.9, 1.1) for i in range(m)]
            kn = sorted(kn)
            if r.random() < 0.5:
                kn = [-x for x in reversed(kn)]
        else:
            kn = [0.15 * (i + 1) for i in range(m)]
            if r.random() < 0.5:
                kn = [-x for x in reversed(kn)]
        me = self.name("P")
        self.meshes[me] = {"polar": lab, "u": self.arcs(), "v": {"knots": kn}}
        self.tags.append("polar-" + kind)
        cur = me
        sz = self.size_of(pl) * 2
        if kind in ("sphere", "ellipsoid") and r.random() < 0.5:
            mo = self.name("M")
            if r.random() < 0.6:
                self.meshes[mo] = {"mobius": cur, "sphere": lab, "b": r.choice([r.uniform(-2, 2), 0.5, -0.3, 1.0])}
                self.tags.append("mobius-b")
            else:
                # poles on the unit sphere placed: only for a sphere whose placement we know
                if kind == "sphere" and not isinstance(pl.get("scale", 1.0), list):
                    rad = sh["radius"]
                    def onsph():
                        v = [r.gauss(0, 1) for _ in range(3)]
                        n = math.sqrt(sum(x * x for x in v))
                        return [x / n for x in v]
                    a = onsph()
                    lim = r.choice([0.2, 0.6, 0.9, 0.97])
                    while True:
                        b = onsph()
                        if sum(x * y for x, y in zip(a, b)) < lim:
                            break
                    # world coordinates: placement = scale, rotate, translate
                    def place(p):
                        s = pl.get("scale", 1.0)
                        q = [x * rad * s for x in p]
                        rots = pl.get("rotate")
                        if rots:
                            for ro in (rots if isinstance(rots, list) else [rots]):
                                q = rotate(q, ro["axis"], ro["degrees"])
                        t = pl.get("translate", [0, 0, 0])
                        return [q[k] + t[k] for k in range(3)]
                    self.meshes[mo] = {"mobius": cur, "sphere": lab, "poles": {"south": place(a), "north": place(b)}}
                    self.tags.append("mobius-poles")
                else:
                    self.meshes[mo] = {"mobius": cur, "sphere": lab, "b": r.uniform(-1, 1)}
                    self.tags.append("mobius-b")
            cur = mo
        ends = ["south", "north"] if kind in ("sphere", "ellipsoid") else (["south"] if kn[0] > 0 else ["north"])
        if r.random() < 0.5:
            ed = self.name("E")
            pts = []
            if r.random() < 0.5:
                e = r.choice(ends)
                pts.append({"pole": e, "move": [sz * r.uniform(-0.05, 0.05) for _ in range(3)]})
                self.tags.append("pole-move")
            if r.random() < 0.6:
                # near (not at) a pole: the row next to it
                # the polar mesh has m + 2 rows, 0 and m + 1 at the poles
                row = 1 if r.random() < 0.5 else m
                i = r.randrange(self.count_u(self.meshes[me]["u"]))
                mag = sz * 10 ** r.uniform(-9, -2)
                pts.append({"at": [i, row],
                            "move": [mag * r.uniform(-1, 1) for _ in range(3)]})
                self.tags.append("near-pole-edit")
            if r.random() < 0.3:
                pts.append({"pole": r.choice(ends), "W": r.uniform(0.5, 2)})
                self.tags.append("pole-W")
            if pts:
                self.meshes[ed] = {"edit": cur, "points": pts}
                if r.random() < 0.4:
                    mo = self.name("T")
                    self.meshes[mo] = {"morph": [cur, ed], "t": r.choice([0.5, r.uniform(0, 1), 0.25])}
                    self.tags.append("morph")
                    cur = mo
                else:
                    cur = ed
        if r.random() < 0.3:
            tr = self.name("X")
            pl2 = self.placement()
            if not pl2:
                pl2 = {"translate": [1, 2, 3]}
            self.meshes[tr] = dict({"transform": cur}, **pl2)
            self.tags.append("transform")
            cur = tr
        cap = self.name("C")
        c = {"cap": cur}
        e = r.choice(["both", "both", "south", "north"]) if kind in ("sphere", "ellipsoid") else ends[0]
        if e != "both":
            c["ends"] = e
        elif r.random() < 0.3:
            c["ends"] = "both"
        if r.random() < 0.25:
            c["quadratic"] = "general"
            self.tags.append("general")
        self.meshes[cap] = c
        self.outputs.append(cap)
        if r.random() < 0.15:
            self.outputs.append(cur)  # the uncapped band too

    def count_u(self, u):
        a = u["arcs"]
        return a if isinstance(a, int) else len(a)

    def tube(self):
        """caps on tubes: a cylinder, a cone (away from its apex) or a transposed torus/cyclide piece,
        maybe edited, capped"""
        r = self.r
        kind = r.choice(["cylinder", "cone", "torus", "cyclide"])
        lab = self.name("t")
        pl = self.placement()
        sh = {"kind": kind}
        if kind == "cylinder":
            sh["radius"] = r.uniform(0.3, 2)
        elif kind == "cone":
            sh["k"] = r.uniform(0.5, 2)
        elif kind == "torus":
            R = r.uniform(2, 4)
            sh.update(R=R, r=r.uniform(0.3, 1))
        else:
            sh.update(a=2, c=r.uniform(0.5, 1), mu=1.5)
        sh.update(pl)
        self.shapes[lab] = sh
        me = self.name("B")
        if kind in ("cylinder", "cone"):
            lo = r.uniform(0.5, 1.5)
            self.meshes[me] = {"shape": lab, "u": self.arcs(), "v": {"segments": r.randint(2, 6), "from": lo, "to": lo + r.uniform(1, 3)}}
            cur = me
        else:
            self.meshes[me] = {"shape": lab, "u": {"arcs": r.randint(2, 5), "from": 0, "to": r.choice([60, 90, 120, 150])},
                               "v": {"arcs": r.randint(6, 10)}}
            tp = self.name("Tp")
            self.meshes[tp] = {"transpose": me}
            cur = tp
        self.tags.append("tube-" + kind)
        if r.random() < 0.4:
            ed = self.name("E")
            sz = self.size_of(pl)
            self.meshes[ed] = {"edit": cur, "points": [{"at": [r.randrange(3), r.randrange(1, 3)], "move": [sz * r.uniform(-0.2, 0.2) for _ in range(3)]}]}
            cur = ed
            self.tags.append("tube-edit")
        cap = self.name("C")
        c = {"cap": cur, "ends": r.choice(["both", "south", "north"])}
        if r.random() < 0.2:
            c["quadratic"] = "general"
            self.tags.append("general")
        if r.random() < 0.2:
            c["length"] = [r.uniform(0.8, 3), r.uniform(0.8, 3)]
            c["vc"] = [r.uniform(0, 0.6), r.uniform(0, 0.6)]
        self.meshes[cap] = c
        self.outputs.append(cap)

    def capsule(self):
        """Fig. 10: the south half of a polar sphere merged with a cylinder, capped (both shapes placed alike)"""
        r = self.r
        pl = self.placement()
        a, b = self.name("s"), self.name("c")
        self.shapes[a] = dict({"kind": "sphere", "radius": 1}, **pl)
        self.shapes[b] = dict({"kind": "cylinder", "radius": 1}, **pl)
        n = r.choice([6, 8, 10])
        p, h, t, m, c = self.name("P"), self.name("H"), self.name("Y"), self.name("J"), self.name("C")
        self.meshes[p] = {"polar": a, "u": {"arcs": n}, "v": {"knots": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]}}
        self.meshes[h] = {"cut": p, "v": [0, 6]}
        self.meshes[t] = {"shape": b, "u": {"arcs": n}, "v": {"segments": r.randint(3, 8), "from": 0.8, "to": 0.8 + r.uniform(1, 3)}}
        self.meshes[m] = {"merge": [h, t], "along": "v"}
        cur = m
        if r.random() < 0.5:
            e = self.name("E")
            self.meshes[e] = {"edit": m, "points": [{"pole": "south", "move": [r.uniform(-0.05, 0.05) * self.size_of(pl) for _ in range(3)]}]}
            cur = e
        self.meshes[c] = {"cap": cur}
        if r.random() < 0.3:
            self.meshes[c]["quadratic"] = "general"
        self.outputs.append(c)
        self.tags.append("capsule")

    def apex(self):
        """a cone or paraboloid shape mesh through its apex (v = 0 a collapsed row), at the start, the end or
        inside the v range; maybe transposed (pole along u) or reversed"""
        r = self.r
        kind = r.choice(["cone", "paraboloid"])
        lab = self.name("a")
        pl = self.placement()
        sh = {"kind": kind}
        if kind == "cone":
            sh["k"] = r.uniform(0.5, 2)
        else:
            sh.update(A=r.uniform(0.5, 2), B=r.uniform(0.5, 2))
        sh.update(pl)
        self.shapes[lab] = sh
        n = r.randint(2, 4)
        where = r.choice(["start", "end", "inside"])
        h = r.uniform(0.2, 0.5)
        if where == "start":
            kn = [h * k for k in range(n + 1)]
        elif where == "end":
            kn = [-h * k for k in range(n, -1, -1)]
        else:
            kn = [h * k for k in range(-n, n + 1)]
        me = self.name("A")
        u = self.arcs() if r.random() < 0.7 else {"arcs": r.randint(2, 5), "from": 0, "to": r.choice([90, 180, 270])}
        self.meshes[me] = {"shape": lab, "u": u, "v": {"knots": kn}}
        self.tags.append("apex-%s-%s" % (kind, where))
        cur = me
        if r.random() < 0.4:
            t = self.name("R")
            self.meshes[t] = {"reverse": cur, "dir": r.choice(["u", "v"])}
            cur = t
            self.tags.append("reverse")
        if r.random() < 0.5:
            t = self.name("Tp")
            self.meshes[t] = {"transpose": cur}
            cur = t
            self.tags.append("pole-along-u")
        self.outputs.append(cur)

    def nurbs(self):
        """a clamped NURBS whose end row or column is collapsed (with weights), or nearly (a short side)"""
        r = self.r
        nu, nv = r.randint(4, 7), r.randint(4, 7)
        along = r.choice(["v0", "v1", "u0", "u1"])
        short = r.random() < 0.6
        pl = self.placement()
        s = self.size_of(pl)
        t = pl.get("translate", [0, 0, 0])
        ang = r.uniform(0, 2 * math.pi)
        pts, W = [], []
        delta = (10 ** r.uniform(-17, -10) if r.random() < 0.5 else 10 ** r.uniform(-16, -13)) if short else 0.0
        spread = r.choice([0.0, 0.2, 1.0, 2.0, 3.0])
        for i in range(nu):
            for j in range(nv):
                # polar coordinates: rho from the collapsed line
                if along[0] == "v":
                    rho = (j if along == "v0" else nv - 1 - j) / (nv - 1)
                    th = ang + math.pi * 1.2 * i / (nu - 1)
                else:
                    rho = (i if along == "u0" else nu - 1 - i) / (nu - 1)
                    th = ang + math.pi * 1.2 * j / (nv - 1)
                p = [rho * math.cos(th), rho * math.sin(th), 0.4 * rho * rho + 0.1 * math.sin(3 * th) * rho]
                p = [s * x + t[k] for k, x in enumerate(p)]
                pts.append(p)
                W.append(math.exp(spread * r.uniform(-1, 1)))
        if short:
            # one point of the collapsed line moved off by delta of the size
            if along[0] == "v":
                i, j = r.randrange(nu), (0 if along == "v0" else nv - 1)
            else:
                i, j = (0 if along == "u0" else nu - 1), r.randrange(nv)
            k = i * nv + j
            pts[k] = [pts[k][c] + delta * s * r.uniform(-1, 1) for c in range(3)]
            self.tags.append("short-%.0e" % delta)
        def kv(n):
            if r.random() < 0.7:
                inner = sorted(r.uniform(0, 1) for _ in range(n - 4))
                inner = [0.1 + 0.8 * (k + 1) / (n - 3) for k in range(n - 4)] if any(
                    b - a < 0.05 for a, b in zip([0] + inner, inner + [1])) else inner
                return [0, 0, 0, 0] + inner + [1, 1, 1, 1]
            return [float(k) for k in range(n + 4)]
        ku, kvv = kv(nu), kv(nv)
        # a clamped end at the collapsed line (else the line is no patch side)
        clamp = lambda n: [0, 0, 0, 0] + [0.1 + 0.8 * (k + 1) / (n - 3) for k in range(n - 4)] + [1, 1, 1, 1]
        if along[0] == "v":
            kvv = clamp(nv)
        else:
            ku = clamp(nu)
        me = self.name("N")
        self.meshes[me] = {"nurbs": {"nu": nu, "nv": nv, "points": pts, "weights": W, "knots_u": ku, "knots_v": kvv}}
        self.tags.append("nurbs-" + along)
        cur = me
        if r.random() < 0.3:
            tp = self.name("Tp")
            self.meshes[tp] = {"transpose": cur}
            cur = tp
        self.outputs.append(cur)


def rotate(p, axis, deg):
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    R = [[c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
         [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
         [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)]]
    return [sum(R[i][k] * p[k] for k in range(3)) for i in range(3)]


def make(seed):
    r = random.Random(seed)
    g = G(r)
    for _ in range(r.choice([1, 1, 2, 2, 3])):
        t = r.random()
        if t < 0.4:
            g.polar()
        elif t < 0.5:
            g.capsule()
        elif t < 0.7:
            g.tube()
        elif t < 0.85:
            g.apex()
        else:
            g.nurbs()
    d = {"format": "rg2 design 1", "description": "random pole design %d: %s" % (seed, ", ".join(g.tags)),
         "shapes": g.shapes, "meshes": g.meshes, "output": g.outputs}
    return d, g.tags



EPS = sys.float_info.epsilon
ULPS = 16


class Surf:
    def __init__(self, js):
        self.nu, self.nv = js["nu"], js["nv"]
        self.cu, self.cv = js["closed_u"], js["closed_v"]
        self.du, self.dv = js["du"], js["dv"]
        self.P = []
        for p, raw in enumerate(js["patches"]):
            du, dv = self.du[p], self.dv[p]
            raw = [float(x) for x in raw]
            self.P.append([[raw[4 * (r * (dv + 1) + q):4 * (r * (dv + 1) + q) + 4] for q in range(dv + 1)]
                           for r in range(du + 1)])
        lo, hi = [math.inf] * 3, [-math.inf] * 3
        for X in self.P:
            for row in X:
                for h in row:
                    for d in range(3):
                        x = h[d] / h[3]
                        if math.isfinite(x):
                            lo[d], hi[d] = min(lo[d], x), max(hi[d], x)
        self.big = max(max(abs(x) for x in lo), max(abs(x) for x in hi))
        self.tol = 1e-11 * math.sqrt(sum((hi[d] - lo[d]) ** 2 for d in range(3)))
        self.ptol = ULPS * EPS * self.big
        self.diag = math.sqrt(sum((hi[d] - lo[d]) ** 2 for d in range(3)))

    def patch(self, i, j):
        return self.P[i * self.nv + j]


def side_pts(X, side):
    du, dv = len(X) - 1, len(X[0]) - 1
    if side == 0:
        return [(r, 0) for r in range(du + 1)]
    if side == 1:
        return [(du, q) for q in range(dv + 1)]
    if side == 2:
        return [(r, dv) for r in range(du + 1)]
    return [(0, q) for q in range(dv + 1)]


def q3(h):
    return (h[0] / h[3], h[1] / h[3], h[2] / h[3])


def topology(s):
    """expected written point of every (patch, r, q): dict, and figures"""
    nu, nv = s.nu, s.nv
    par = list(range((nu + 1) * (nv + 1)))

    def find(a):
        while par[a] != a:
            a = par[a]
        return a

    def union(a, b):
        a, b = find(a), find(b)
        if a != b:
            par[max(a, b)] = min(a, b)

    C = lambda I, J: I * (nv + 1) + J
    for I in range(nu + 1):
        for J in range(nv + 1):
            union(C(I, J), C(0 if (s.cu and I == nu) else I, 0 if (s.cv and J == nv) else J))
    # grid edges: ('u', I, j) along u-line I over span j; ('v', J, i)
    def edge(i, j, side):
        if side == 0:
            e = ("v", j, i)
        elif side == 1:
            e = ("u", i + 1, j)
        elif side == 2:
            e = ("v", j + 1, i)
        else:
            e = ("u", i, j)
        if e[0] == "u" and s.cu and e[1] == nu:
            e = ("u", 0, e[2])
        if e[0] == "v" and s.cv and e[1] == nv:
            e = ("v", 0, e[2])
        return e

    def ends(i, j, side):
        return {0: (C(i, j), C(i + 1, j)), 1: (C(i + 1, j), C(i + 1, j + 1)), 2: (C(i, j + 1), C(i + 1, j + 1)),
                3: (C(i, j), C(i, j + 1))}[side]

    coll = set()
    for i in range(nu):
        for j in range(nv):
            X = s.patch(i, j)
            for side in range(4):
                pts = [q3(X[r][q]) for r, q in side_pts(X, side)]
                if all(abs(p[d] - pts[0][d]) <= s.tol for p in pts[1:] for d in range(3)):
                    coll.add(edge(i, j, side))
    for i in range(nu):
        for j in range(nv):
            for side in range(4):
                if edge(i, j, side) in coll:
                    union(*ends(i, j, side))
    # the points each vertex class would replace
    members = {}
    for i in range(nu):
        for j in range(nv):
            X = s.patch(i, j)
            for side in range(4):
                if edge(i, j, side) in coll:
                    v = find(ends(i, j, side)[0])
                    for r, q in side_pts(X, side):
                        members.setdefault(v, set()).add((i, j, r, q))
    cand = set(members)
    for i in range(nu):
        for j in range(nv):
            X = s.patch(i, j)
            du, dv = len(X) - 1, len(X[0]) - 1
            for r, q in ((0, 0), (du, 0), (0, dv), (du, dv)):
                v = find(C(i + (r > 0), j + (q > 0)))
                if v in cand:
                    members[v].add((i, j, r, q))
    poles = {}
    for v, mem in members.items():
        I, J = v // (nv + 1), v % (nv + 1)
        i, j = min(I, nu - 1), min(J, nv - 1)
        X = s.patch(i, j)
        h = X[0 if I == i else len(X) - 1][0 if J == j else len(X[0]) - 1]
        pole = q3(h)
        devx = Fraction(0)   # the exact spread (the decision below is the rule's, in doubles)
        for (a, b, r, q) in mem:
            g = s.patch(a, b)[r][q]
            for d in range(3):
                devx = max(devx, abs(Fraction(g[d]) / Fraction(g[3]) - Fraction(pole[d])))
        ws = [abs(s.patch(a, b)[r][q][3]) for (a, b, r, q) in mem]
        ratio = max(ws) / min(ws) if min(ws) > 0 else 1.0
        ratio = ratio if ratio > 1.0 and math.isfinite(ratio) else 1.0
        snap = all(abs(s.patch(a, b)[r][q][d] / s.patch(a, b)[r][q][3] - pole[d]) <= s.ptol * ratio
                   for (a, b, r, q) in mem for d in range(3))
        poles[v] = dict(pole=pole, snap=snap, mem=mem, ratio=ratio,
                        devx=float(devx) / (EPS * s.big) if s.big else 0.0, n=len(mem))
    expect = {}
    for i in range(nu):
        for j in range(nv):
            X = s.patch(i, j)
            for r in range(len(X)):
                for q in range(len(X[0])):
                    expect[i, j, r, q] = q3(X[r][q])
    snapped = {}
    for v, P in poles.items():
        if P["snap"]:
            for m in P["mem"]:
                expect[m] = P["pole"]
                snapped[m] = P["pole"]
    return expect, poles, coll, snapped


# ---------------------------------------------------------------- readers
def read_step(path):
    text = open(path).read()
    ents = {}
    for m in re.finditer(r"#(\d+)=(.*?);\s*$", text, re.S | re.M):
        ents[int(m.group(1))] = m.group(2)
    pts = {}
    for k, e in ents.items():
        if e.startswith("CARTESIAN_POINT('',("):
            pts[k] = tuple(float(x) for x in e[len("CARTESIAN_POINT('',("):e.index(")")].split(","))
    surfs, curves, verts = [], [], []
    for k in sorted(ents):
        e = ents[k]
        m = re.search(r"B_SPLINE_SURFACE\((\d+),(\d+),\((.*?)\),\.[A-Z_]+\.", e, re.S)
        if m and "RATIONAL_B_SPLINE_SURFACE" in e:
            refs = [[int(x) for x in re.findall(r"#(\d+)", row)] for row in re.findall(r"\(([^()]*)\)", m.group(3))]
            wm = re.search(r"RATIONAL_B_SPLINE_SURFACE\((\(.*?\)\))\)", e, re.S)
            ws = [[float(x) for x in row.split(",")] for row in re.findall(r"\(([^()]*)\)", wm.group(1))]
            surfs.append([[(pts[refs[a][b]], ws[a][b]) for b in range(len(refs[a]))] for a in range(len(refs))])
            continue
        m = re.search(r"B_SPLINE_CURVE\((\d+),\(([^()]*)\)", e, re.S)
        if m:
            refs = [int(x) for x in re.findall(r"#(\d+)", m.group(2))]
            curves.append([pts[x] for x in refs])
            continue
        if e.startswith("VERTEX_POINT("):
            verts.append(pts[int(re.search(r"#(\d+)", e).group(1))])
    return surfs, curves, verts


def read_iges(path):
    params = {}
    for line in open(path):
        if len(line) >= 73 and line[72] == "P":
            params.setdefault(int(line[64:72]), []).append(line[:64])
    surfs, curves, verts = [], [], []
    for k, v in sorted(params.items()):
        e = "".join(v).replace("D", "E")
        f = e.split(";")[0].split(",")
        t = int(f[0])
        if t == 128:
            K1, K2, M1, M2 = (int(x) for x in f[1:5])
            k0 = 10 + (K1 + M1 + 2) + (K2 + M2 + 2)
            nw = (K1 + 1) * (K2 + 1)
            ws = [float(x) for x in f[k0:k0 + nw]]
            xyz = [float(x) for x in f[k0 + nw:k0 + 4 * nw]]
            surfs.append([[(tuple(xyz[3 * (b * (K1 + 1) + a):3 * (b * (K1 + 1) + a) + 3]), ws[b * (K1 + 1) + a])
                           for b in range(K2 + 1)] for a in range(K1 + 1)])
        elif t == 126:
            K, M = int(f[1]), int(f[2])
            k0 = 7 + (K + M + 2)
            xyz = [float(x) for x in f[k0 + K + 1:k0 + 4 * (K + 1)]]
            curves.append([tuple(xyz[3 * a:3 * a + 3]) for a in range(K + 1)])
        elif t == 502:
            n = int(f[1])
            xyz = [float(x) for x in f[2:2 + 3 * n]]
            verts.extend(tuple(xyz[3 * a:3 * a + 3]) for a in range(n))
    return surfs, curves, verts


# ---------------------------------------------------------------- checks
def check_files(dump, pps, ppi, bpi, pms, pmi, bmi):
    """one design's files: the figures, with fig["fails"] the failures found"""
    S = [Surf(x) for x in json.load(open(dump))["surfaces"]]
    fails = []
    fig = {"surfaces": len(S), "patches": sum(s.nu * s.nv for s in S), "poles": 0, "pole_points": 0,
           "short": 0, "max_pole_dev": 0.0, "min_short_margin": None, "collapsed_sides": 0,
           "lib_seam_mismatch": 0, "points": 0}
    T = [topology(s) for s in S]
    fig["per_surface"] = []
    for s, (expect, poles, coll, _) in zip(S, T):
        fig["per_surface"].append([max([P["devx"] for P in poles.values() if P["snap"]] or [0.0]),
                                   min([P["devx"] for P in poles.values() if not P["snap"]] or [-1.0]),
                                   sum(1 for P in poles.values() if P["snap"]), sum(1 for P in poles.values() if not P["snap"])])
        fig["collapsed_sides"] += len(coll)
        for v, P in poles.items():
            if P["snap"]:
                fig["poles"] += 1
                fig["pole_points"] += P["n"]
                fig["max_pole_dev"] = max(fig["max_pole_dev"], P["devx"])
            else:
                fig["short"] += 1
                m = P["devx"] / P["ratio"] - ULPS  # (in roundings times the weights' ratio)
                fig["min_short_margin"] = m if fig["min_short_margin"] is None else min(fig["min_short_margin"], m)

    def fail(msg):
        if len(fails) < 30:
            fails.append(msg)

    def same(a, b):
        return tuple(a) == tuple(b)

    def judge_weight(fmt, where, w, h3, f):
        if not (w > 0):
            fail("%s %s weight %r <= 0" % (fmt, where, w))
        if w != h3 * f:
            fail("%s %s weight %r, dump %r (factor %r)" % (fmt, where, w, h3, f))

    def per_patch(fmt, surfs, curves, verts, iges):
        k = 0
        for si, s in enumerate(S):
            expect = T[si][0]
            written = {}
            for i in range(s.nu):
                for j in range(s.nv):
                    if k >= len(surfs):
                        fail("%s: too few surfaces" % fmt)
                        return
                    net = surfs[k]
                    k += 1
                    X = s.patch(i, j)
                    if len(net) != len(X) or len(net[0]) != len(X[0]):
                        fail("%s s%d (%d,%d) degrees" % (fmt, si, i, j))
                        continue
                    f = 1.0
                    if iges:
                        f = net[0][0][1] / X[0][0][3]
                        if f != 1.0 and math.frexp(f)[0] != 0.5:
                            fail("%s weight factor %r not a power of 2" % (fmt, f))
                    for r in range(len(X)):
                        for q in range(len(X[0])):
                            p, w = net[r][q]
                            fig["points"] += 1
                            written[i, j, r, q] = p
                            judge_weight(fmt, "s%d (%d,%d)[%d][%d]" % (si, i, j, r, q), w, X[r][q][3], f)
                            e = expect[i, j, r, q]
                            if not same(p, e):
                                fail("%s s%d (%d,%d)[%d][%d] written %r expected %r (h/w %r)" % (
                                    fmt, si, i, j, r, q, p, e, q3(X[r][q])))
            # (b) neighbours' shared boundary rows
            for i in range(s.nu):
                for j in range(s.nv):
                    X = s.patch(i, j)
                    du, dv = len(X) - 1, len(X[0]) - 1
                    if i + 1 < s.nu or s.cu:
                        i2 = (i + 1) % s.nu
                        Y = s.patch(i2, j)
                        for q in range(dv + 1):
                            if len(Y[0]) == dv + 1 and not same(written[i, j, du, q], written[i2, j, 0, q]):
                                fail("%s s%d seam u (%d,%d)|(%d,%d) q %d: %r vs %r" % (
                                    fmt, si, i, j, i2, j, q, written[i, j, du, q], written[i2, j, 0, q]))
                            if fmt.startswith("STEP") and len(Y[0]) == dv + 1 and list(X[du][q]) != list(Y[0][q]):
                                fig["lib_seam_mismatch"] += 1
                    if j + 1 < s.nv or s.cv:
                        j2 = (j + 1) % s.nv
                        Y = s.patch(i, j2)
                        for r in range(du + 1):
                            if len(Y) == du + 1 and not same(written[i, j, r, dv], written[i, j2, r, 0]):
                                fail("%s s%d seam v (%d,%d)|(%d,%d) r %d: %r vs %r" % (
                                    fmt, si, i, j, i, j2, r, written[i, j, r, dv], written[i, j2, r, 0]))
                            if fmt.startswith("STEP") and len(Y) == du + 1 and list(X[r][dv]) != list(Y[r][0]):
                                fig["lib_seam_mismatch"] += 1
            # poles: one point across the patches
            for v, P in T[si][1].items():
                if P["snap"]:
                    got = {written[m] for m in P["mem"]}
                    if len(got) != 1:
                        fail("%s s%d pole %r written as %d points" % (fmt, si, P["pole"], len(got)))
            # collapsed sides one point
            for i in range(s.nu):
                for j in range(s.nv):
                    X = s.patch(i, j)
                    for side in range(4):
                        pts = [q3(X[r][q]) for r, q in side_pts(X, side)]
                        if all(abs(p[d] - pts[0][d]) <= s.tol for p in pts[1:] for d in range(3)):
                            got = {written[i, j, r, q] for r, q in side_pts(X, side)}
                            snapped = any(P["snap"] and (i, j, side_pts(X, side)[0][0], side_pts(X, side)[0][1]) in P["mem"]
                                          for P in T[si][1].values())
                            if len(got) != 1 and snapped:
                                fail("%s s%d (%d,%d) collapsed side %d written as %d points" % (fmt, si, i, j, side, len(got)))
        if k != len(surfs):
            fail("%s: %d surfaces for %d patches" % (fmt, len(surfs), k))
        check_vc(fmt, surfs, curves, verts)

    def check_vc(fmt, surfs, curves, verts):
        allpts = set()
        for net in surfs:
            for row in net:
                for p, w in row:
                    allpts.add(tuple(p))
        for v in verts:
            if tuple(v) not in allpts:
                fail("%s vertex %r is no control point of a face" % (fmt, v))
        for c in curves:
            for p in c:
                if tuple(p) not in allpts:
                    fail("%s edge curve point %r is no control point of a face" % (fmt, p))

    def per_mesh(fmt, surfs, curves, verts, iges):
        if len(surfs) != len(S):
            fail("%s: %d surfaces for %d meshes" % (fmt, len(surfs), len(S)))
            return
        for si, (s, net) in enumerate(zip(S, surfs)):
            du = max(s.du)
            dv = max(s.dv)
            if min(s.du) != du or min(s.dv) != dv:
                fig["mixed_degree"] = 1
                continue
            NU, NV = du * s.nu + 1, dv * s.nv + 1
            if len(net) != NU or len(net[0]) != NV:
                fail("%s s%d net %dx%d, expected %dx%d" % (fmt, si, len(net), len(net[0]), NU, NV))
                continue
            f = 1.0
            if iges:
                f = net[0][0][1] / s.patch(0, 0)[0][0][3]
            for a in range(NU):
                for b in range(NV):
                    aa = 0 if (s.cu and a == NU - 1) else a
                    bb = 0 if (s.cv and b == NV - 1) else b
                    # lowest patch holding it
                    i = max(0, (aa - 1) // du) if aa > 0 else 0
                    i = min(i, s.nu - 1)
                    j = max(0, (bb - 1) // dv) if bb > 0 else 0
                    j = min(j, s.nv - 1)
                    r, q = aa - du * i, bb - dv * j
                    X = s.patch(i, j)
                    p, w = net[a][b]
                    fig["points"] += 1
                    judge_weight(fmt, "s%d net [%d][%d]" % (si, a, b), w, X[r][q][3], f)
                    # the patch the writer asks (the one after a line; the last on the last line)
                    ia, jb = min(a // du, s.nu - 1), min(b // dv, s.nv - 1)
                    key = (ia, jb, a - du * ia, b - dv * jb)
                    want = T[si][3][key] if key in T[si][3] else q3(X[r][q])
                    if not same(p, want):
                        fail("%s s%d net [%d][%d] written %r expected %r" % (fmt, si, a, b, p, want))
        check_vc(fmt, surfs, curves, verts)

    R = {}
    R["STEP pp"] = read_step(pps)
    R["IGES pp"] = read_iges(ppi)
    R["IGES brep pp"] = read_iges(bpi)
    R["STEP pm"] = read_step(pms)
    R["IGES pm"] = read_iges(pmi)
    R["IGES brep pm"] = read_iges(bmi)
    for k in ("STEP pp", "IGES pp", "IGES brep pp"):
        per_patch(k, *R[k], k.startswith("IGES"))
    for k in ("STEP pm", "IGES pm", "IGES brep pm"):
        per_mesh(k, *R[k], k.startswith("IGES"))
    # the same points in every form of one layout
    for a, b in (("STEP pp", "IGES pp"), ("STEP pp", "IGES brep pp"), ("STEP pm", "IGES pm"), ("STEP pm", "IGES brep pm")):
        A, B = R[a][0], R[b][0]
        nd = sum(1 for x, y in zip(A, B) for ra, rb in zip(x, y) for pa, pb in zip(ra, rb) if tuple(pa[0]) != tuple(pb[0]))
        if nd or len(A) != len(B):
            fail("%s and %s differ at %d points" % (a, b, nd))
    fig["fails"] = fails
    return fig



def run(rg2, n, first):
    tot = {"designs": 0, "refused": 0, "surfaces": 0, "patches": 0, "poles": 0, "short": 0, "points": 0,
           "max_pole_dev": 0.0, "min_short_dev": None}
    failed = []
    with tempfile.TemporaryDirectory(prefix="rg2-poles-") as tmp:
        for seed in range(first, first + n):
            d, tags = make(seed)
            base = os.path.join(tmp, "d%d" % seed)
            with open(base + ".json", "w") as f:
                json.dump(d, f)
            tot["designs"] += 1
            forms = ((["-o", base + ".patches.json", "-o", base + ".pp.step", "-o", base + ".pp.igs"]),
                     (["--iges-brep", "-o", base + ".bp.igs"]),
                     (["--face-per-mesh", "-o", base + ".pm.step", "-o", base + ".pm.igs"]),
                     (["--face-per-mesh", "--iges-brep", "-o", base + ".bm.igs"]))
            rs = [subprocess.run([rg2, "build", base + ".json", "-q"] + x, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True) for x in forms]
            if rs[0].returncode:
                tot["refused"] += 1
                continue
            if any(x.returncode for x in rs[1:]):
                failed.append("design %d: a layout failed where face per patch was written: %s" % (
                    seed, " | ".join(x.stderr.strip() for x in rs)))
                continue
            fig = check_files(*(base + e for e in (".patches.json", ".pp.step", ".pp.igs", ".bp.igs", ".pm.step",
                                                    ".pm.igs", ".bm.igs")))
            for k in ("surfaces", "patches", "poles", "short", "points"):
                tot[k] += fig[k]
            tot["max_pole_dev"] = max(tot["max_pole_dev"], fig["max_pole_dev"])
            if fig["min_short_margin"] is not None:
                m = fig["min_short_margin"] + ULPS
                tot["min_short_dev"] = m if tot["min_short_dev"] is None else min(tot["min_short_dev"], m)
            if fig["fails"]:
                failed.append("design %d (%s):\n      %s" % (seed, ", ".join(tags), "\n      ".join(fig["fails"][:6])))
    print("%d random pole designs (%d refused by rg2), %d surfaces, %d patches, %d control points in 6 layouts: "
          "%d poles written as one point (largest spread of a pole's points h / w %.3g roundings), %d short "
          "sides kept (smallest spread, over its weights' ratio, %s roundings)" % (
              tot["designs"], tot["refused"], tot["surfaces"], tot["patches"], tot["points"], tot["poles"],
              tot["max_pole_dev"], tot["short"], "%.3g" % tot["min_short_dev"] if tot["min_short_dev"] is not None else "-"))
    if tot["refused"] * 5 > tot["designs"]:
        failed.append("%d of %d designs refused" % (tot["refused"], tot["designs"]))
    for f in failed:
        print("FAIL " + f)
    print("FAIL" if failed else "ok")
    return 1 if failed else 0


def main(argv):
    if len(argv) not in (1, 2, 3):
        print(__doc__[__doc__.index("Usage:"):], file=sys.stderr)
        return 2
    try:
        n = int(argv[1]) if len(argv) > 1 else 120
        first = int(argv[2]) if len(argv) > 2 else 1
    except ValueError:
        print(__doc__[__doc__.index("Usage:"):], file=sys.stderr)
        return 2
    return run(argv[0], n, first)


if __name__ == "__main__":
    if sys.version_info < (3, 8):
        print("pole_audit: error: needs Python 3.8 or later", file=sys.stderr)
        sys.exit(1)
    sys.exit(main(sys.argv[1:]))
