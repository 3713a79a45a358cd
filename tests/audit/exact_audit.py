#!/usr/bin/env python3
"""exact_audit.py -- an audit of rg2's geometry that shares no code with the library.

It reads what `rg2 build` writes for every design in examples/ and two of its own (every named
shape, placed; capped polar meshes of four quadrics: OWN_DESIGNS below) (the patch dump `x.json`:
homogeneous control points, degrees and shape tags; the same build's `.bv` and `.bez`) and what
`rg2 mesh` writes (the control mesh: d, W, the scalars w, b, g, and the shapes with their
parameters and placement matrices), takes every double in them as the exact number it is, and
measures in 50-digit decimal arithmetic (the decimal module; the doubles enter exactly) or in
exact rationals (fractions.Fraction):

  exact         every patch tagged with a shape lies on that shape's implicit surface
                (docs/MATH.md section 5, docs/shapes.md): max |F| / (|grad F| size) over 7 x 7
                samples per patch, size the diagonal of the box of the control points of the
                shape's patches (as rg2 check);
  G0, G1, G2    across every seam between neighbouring patches of a surface (the closing seams
                of closed directions included), at 7 points along it: the position gap / size,
                the angle between the normals, and the jump of the normal curvature in six
                tangent directions relative to max(|k1|, |k2|, 1 / size), from exact first and
                second derivatives of the rational patches (quotient rule, no differences);
  near a pole   a sample on a collapsed side has no normal: there the fan's limit normals
                (Suv x Sv) are compared ("G1 at pole"), and G1 / G2 are measured 1/100 and 1/10
                into the seam instead ("near pole"). The dump's doubles of a collapsed row are
                one point only to rounding (about 1e-16 of the size, "collapsed"), and the fan's
                limit normals agree to about 1e-13: measured on those doubles, G1 near a pole
                grows as 1/eps and G2 as 1/eps^2 (Fig. 14's third sphere: G2 6e-9 at eps = 1/100,
                4e-5 at 1e-4), which is why the samples stay 1/100 away. The STEP and IGES files
                write a collapsed row as one point: on their doubles G1 / G2 are measured 1/100,
                1e-4 and 1e-6 from the poles ("G1 pole file": within G1's limit at each; "G2 pole
                file": G2 times eps / (1/100), within G2's limit: it grows only as 1/eps), and
                printed with the figures of the points h / w each rounded on its own;
  construction  the Bi-cubic Construction (MATH.md sections 1 and 4) redone in exact rationals
                from the mesh file's control points and scalars, rows then columns, against the
                dump's patches (relative to the patch's largest homogeneous coordinate; a capped
                surface's body rows; a patch stored at a higher degree, D H, by its points);
  NURBS         a design's bi-cubic NURBS cut into Bezier patches by blossoming (standard
                B-spline theory, not MATH.md), each found among the built patches;
  placement     every shape of the design file (scale, rotate, translate, matrix) composed here
                against the matrix the mesh file gives it, so that "exact" measures against the
                shape the design asked for; a sphere or cylinder made by a transform (translate)
                or a mobius of one is that quadric moved by the translate, or the same quadric;
  pole          the poles a mobius "poles" entry asks for are where the patches collapse;
  export        the .bv holds the dump's doubles bit for bit, the .bez (one degree for the file)
                the exact degree elevation of each patch to a few roundings; the STEP and IGES
                files (face per patch: affine points and weights) every weight bit for bit and
                every coordinate as the correctly rounded quotient h_k / h_w ("STEP/IGES ulp"),
                but a pole's: every side collapsed in the dump is one point bit for bit, the same
                in every patch around the pole ("STEP/IGES one"), within 16 roundings of the
                largest coordinate of each of its points h / w, times the ratio of their
                weights (largest over smallest, at least 1; "STEP/IGES pole"), and the IGES
                points are the STEP ones;
  MATH.md       sections 1, 2 and 7 on exact rational data: G2 (Definition 1) at every junction
                of random polygons, an open arc partition reproduced exactly, and eq. (13)'s
                polar points and scalars from the blossoms (no rounding); a design's polar mesh
                of a sphere has eq. (13)'s points ("eq. (13) poles").

Limits: exact 1e-14 (rg2 check's is 1e-13 on its own double evaluation), G0 1e-12, G1 1e-10 rad,
G2 1e-8 (rg2 check's), construction and NURBS 1e-14, placement 1e-15, collapsed 1e-14, export
1e-15, a pole's point in STEP/IGES 16 roundings (DBL_EPSILON times the largest coordinate, times
its weights' ratio).

Usage: exact_audit.py RG2 SRC_DIR [--examples a.json,b.json] [--no-self-test] [-v]
       exact_audit.py --files DESIGN PATCHES.json MESH.json   (one design's files as they are)
  RG2 the rg2 command; SRC_DIR the source tree (examples/ under it); -v prints every figure.
  The self-test writes torus_sphere's dump with one control point of an exact patch moved by
  1e-9 of the size (inside the patch, then on its border) and requires the audit to find it off
  its shape, across a seam and against the construction: the audit can fail.
Exit 0 when every figure is within its limit, 1 otherwise (or on an error), 2 on a usage error.
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from decimal import Decimal, getcontext
from fractions import Fraction

getcontext().prec = 50

LIMIT_EXACT = 1e-14
LIMIT_G0 = 1e-12
LIMIT_G1 = 1e-10
LIMIT_G2 = 1e-8
LIMIT_BUILD = 1e-14
LIMIT_PLACE = 1e-15
LIMIT_COLLAPSE = 1e-14
LIMIT_EXPORT = 1e-15     # a few roundings of the largest coordinate (.bez elevation)

RES_N = 6          # residual samples per patch: (RES_N + 1)^2
SEAM_N = 6         # seam samples: SEAM_N + 1 per seam
POLE_STEPS = (Fraction(1, 100), Fraction(1, 10))
POLE_EPS = (Fraction(1, 100), Fraction(1, 10 ** 4), Fraction(1, 10 ** 6))   # on the STEP/IGES doubles
SNAP_ROUNDINGS = 16   # a pole's point from each h / w, in DBL_EPSILON times the largest coordinate

D0 = Decimal(0)
D1 = Decimal(1)


def dec(x):
    """a double (or Fraction) as a 50-digit Decimal: exact, then rounded to 50 digits"""
    if isinstance(x, Fraction):
        return Decimal(x.numerator) / Decimal(x.denominator)
    return +Decimal(x)


def binom(n, k):
    return math.comb(n, k)


# ----------------------------------------------------------------------------------- patches
class Patch:
    __slots__ = ("du", "dv", "raw", "H")

    def __init__(self, du, dv, raw):
        self.du, self.dv, self.raw = du, dv, raw   # raw: 4 (du+1)(dv+1) floats, h[r][s][k]
        self.H = None

    def dec(self):
        if self.H is None:
            n = self.dv + 1
            self.H = [[[dec(self.raw[4 * (r * n + s) + k]) for k in range(4)] for s in range(n)]
                      for r in range(self.du + 1)]
        return self.H

    def point3(self, r, s):
        n = self.dv + 1
        h = self.raw[4 * (r * n + s):4 * (r * n + s) + 4]
        return (h[0] / h[3], h[1] / h[3], h[2] / h[3])


class Surface:
    def __init__(self, js):
        self.nu, self.nv = js["nu"], js["nv"]
        self.closed_u, self.closed_v = js["closed_u"], js["closed_v"]
        self.tag = js.get("tag")
        self.patches = [Patch(js["du"][p], js["dv"][p], [float(x) for x in js["patches"][p]])
                        for p in range(self.nu * self.nv)]
        lo, hi = [math.inf] * 3, [-math.inf] * 3
        for P in self.patches:
            for r in range(P.du + 1):
                for s in range(P.dv + 1):
                    x = P.point3(r, s)
                    for k in range(3):
                        lo[k], hi[k] = min(lo[k], x[k]), max(hi[k], x[k])
        self.size = math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3)))
        self.big = max(max(abs(x) for x in lo), max(abs(x) for x in hi))   # the largest coordinate

    def patch(self, i, j):
        return self.patches[i * self.nv + j]


_bern_cache = {}


def bern(n, t):
    """[B, B', B''] of the degree-n Bernstein polynomials at t (a Fraction), as Decimals"""
    key = (n, t)
    got = _bern_cache.get(key)
    if got is not None:
        return got

    def vals(m):
        if m < 0:
            return []
        return [Fraction(binom(m, k)) * t ** k * (1 - t) ** (m - k) for k in range(m + 1)]

    b0 = vals(n)
    b1m = vals(n - 1)
    b2m = vals(n - 2)
    b1 = [n * ((b1m[k - 1] if 0 <= k - 1 < n else 0) - (b1m[k] if k < n else 0)) for k in range(n + 1)]
    b2 = [n * (n - 1) * ((b2m[k - 2] if 0 <= k - 2 < n - 1 else 0) - 2 * (b2m[k - 1] if 0 <= k - 1 < n - 1 else 0)
                         + (b2m[k] if k < n - 1 else 0)) for k in range(n + 1)]
    got = [[dec(Fraction(x)) for x in b] for b in (b0, b1, b2)]
    _bern_cache[key] = got
    return got


def eval_point(P, u, v):
    """the 3D point of patch P at (u, v) (Fractions), in Decimal"""
    H = P.dec()
    bu, bv = bern(P.du, u)[0], bern(P.dv, v)[0]
    x0 = x1 = x2 = x3 = D0
    for r in range(P.du + 1):
        cu = bu[r]
        if not cu:
            continue
        row = H[r]
        y0 = y1 = y2 = y3 = D0
        for q in range(P.dv + 1):
            c = bv[q]
            if c:
                h = row[q]
                y0 += h[0] * c
                y1 += h[1] * c
                y2 += h[2] * c
                y3 += h[3] * c
        x0 += y0 * cu
        x1 += y1 * cu
        x2 += y2 * cu
        x3 += y3 * cu
    return [x0 / x3, x1 / x3, x2 / x3]


def eval_jet(P, u, v):
    """x, xu, xv, xuu, xuv, xvv of patch P at (u, v): exact quotient rule on the homogeneous
    Bernstein sums (no finite differences), in Decimal"""
    H = P.dec()
    bu, bv = bern(P.du, u), bern(P.dv, v)
    # only the nonzero basis values (on a patch side most of them are 0)
    ru = [r for r in range(P.du + 1) if any(bu[a][r] for a in range(3))]
    sv = [[q for q in range(P.dv + 1) if bv[b][q]] for b in range(3)]
    # C[b][r][k] = sum_s H[r][s][k] B^(b)_s(v)
    C = [{} for b in range(3)]
    for b in range(3):
        bb, qs = bv[b], sv[b]
        for r in ru:
            row = H[r]
            x0 = x1 = x2 = x3 = D0
            for q in qs:
                c, h = bb[q], row[q]
                x0 += h[0] * c
                x1 += h[1] * c
                x2 += h[2] * c
                x3 += h[3] * c
            C[b][r] = (x0, x1, x2, x3)
    X = {}
    for a, b in ((0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)):
        ba, Cb = bu[a], C[b]
        x0 = x1 = x2 = x3 = D0
        for r in ru:
            c = ba[r]
            if c:
                h = Cb[r]
                x0 += h[0] * c
                x1 += h[1] * c
                x2 += h[2] * c
                x3 += h[3] * c
        X[a, b] = (x0, x1, x2, x3)
    w = X[0, 0][3]
    wu, wv, wuu, wuv, wvv = X[1, 0][3], X[0, 1][3], X[2, 0][3], X[1, 1][3], X[0, 2][3]
    x = [X[0, 0][k] / w for k in range(3)]
    xu = [(X[1, 0][k] - x[k] * wu) / w for k in range(3)]
    xv = [(X[0, 1][k] - x[k] * wv) / w for k in range(3)]
    xuu = [(X[2, 0][k] - 2 * xu[k] * wu - x[k] * wuu) / w for k in range(3)]
    xuv = [(X[1, 1][k] - xu[k] * wv - xv[k] * wu - x[k] * wuv) / w for k in range(3)]
    xvv = [(X[0, 2][k] - 2 * xv[k] * wv - x[k] * wvv) / w for k in range(3)]
    return x, xu, xv, xuu, xuv, xvv


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return dot(a, a).sqrt()


# ------------------------------------------------------------------------------------ shapes
def implicit(kind, p, y):
    """f and grad f of the unplaced shape at y (docs/shapes.md's table)"""
    x, yy, z = y
    if kind == "torus":
        R, r = p["R"], p["r"]
        q = x * x + yy * yy + z * z + R * R - r * r
        f = q * q - 4 * R * R * (x * x + yy * yy)
        g = [4 * q * x - 8 * R * R * x, 4 * q * yy - 8 * R * R * yy, 4 * q * z]
    elif kind == "cyclide":
        a, c, mu = p["a"], p["c"], p["mu"]
        b2 = a * a - c * c
        q = x * x + yy * yy + z * z + b2 - mu * mu
        f = q * q - 4 * (a * x - c * mu) ** 2 - 4 * b2 * yy * yy
        g = [4 * q * x - 8 * a * (a * x - c * mu), 4 * q * yy - 8 * b2 * yy, 4 * q * z]
    elif kind in ("sphere", "ellipsoid"):
        if kind == "sphere":
            A = B = C = p["radius"]
        else:
            A, B, C = p["a"], p["b"], p["c"]
        f = x * x / (A * A) + yy * yy / (B * B) + z * z / (C * C) - 1
        g = [2 * x / (A * A), 2 * yy / (B * B), 2 * z / (C * C)]
    elif kind == "cylinder":
        R = p["radius"]
        f = (x * x + yy * yy) / (R * R) - 1
        g = [2 * x / (R * R), 2 * yy / (R * R), D0]
    elif kind == "cone":
        k = p["k"]
        f = k * k * (x * x + yy * yy) - z * z
        g = [2 * k * k * x, 2 * k * k * yy, -2 * z]
    elif kind in ("hyperboloid1", "hyperboloid1_ruled"):
        a, c = p["a"], p["c"]
        f = (x * x + yy * yy) / (a * a) - z * z / (c * c) - 1
        g = [2 * x / (a * a), 2 * yy / (a * a), -2 * z / (c * c)]
    elif kind == "hyperboloid2":
        a, c = p["a"], p["c"]
        f = z * z / (c * c) - (x * x + yy * yy) / (a * a) - 1
        g = [-2 * x / (a * a), -2 * yy / (a * a), 2 * z / (c * c)]
    elif kind == "paraboloid":
        A, B = p["A"], p["B"]
        f = x * x / (A * A) + yy * yy / (B * B) - z
        g = [2 * x / (A * A), 2 * yy / (B * B), -D1]
    elif kind == "hypar":
        A, B = p["A"], p["B"]
        f = x * x / (A * A) - yy * yy / (B * B) - z
        g = [2 * x / (A * A), -2 * yy / (B * B), -D1]
    else:
        raise ValueError("unknown shape kind %r" % kind)
    return f, g


# quadrics as symmetric 4x4 matrices Q (x^T Q x = 0, x homogeneous), for the placement checks
def quadric(kind, p):
    F = Fraction
    if kind in ("sphere", "ellipsoid"):
        if kind == "sphere":
            A = B = C = F(p["radius"])
        else:
            A, B, C = F(p["a"]), F(p["b"]), F(p["c"])
        d = [1 / (A * A), 1 / (B * B), 1 / (C * C), F(-1)]
        return [[d[i] if i == j else F(0) for j in range(4)] for i in range(4)]
    if kind == "cylinder":
        R = F(p["radius"])
        d = [1 / (R * R), 1 / (R * R), F(0), F(-1)]
        return [[d[i] if i == j else F(0) for j in range(4)] for i in range(4)]
    return None


def mat_inv(M):
    """exact inverse of a 4x4 matrix of Fractions (Gauss-Jordan)"""
    n = 4
    A = [list(M[i]) + [Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    for c in range(n):
        piv = next(r for r in range(c, n) if A[r][c] != 0)
        A[c], A[piv] = A[piv], A[c]
        inv = 1 / A[c][c]
        A[c] = [x * inv for x in A[c]]
        for r in range(n):
            if r != c and A[r][c] != 0:
                f = A[r][c]
                A[r] = [x - f * y for x, y in zip(A[r], A[c])]
    return [row[n:] for row in A]


def mat_mul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def transpose(A):
    return [[A[j][i] for j in range(4)] for i in range(4)]


class PlacedShape:
    def __init__(self, js):
        self.label, self.kind = js["label"], js["kind"]
        self.params = {k: v for k, v in js.items() if k not in ("label", "kind", "matrix")}
        self.pdec = {k: dec(v) for k, v in self.params.items()}
        self.M = [[Fraction(js["matrix"][4 * i + j]) for j in range(4)] for i in range(4)]
        self.Minv = mat_inv(self.M)
        self.Mi = [[dec(x) for x in row] for row in self.Minv]

    def residual(self, x):
        """|F| / |grad F| at the placed point x (3 Decimals): F(phi(x)), phi = M^-1 projectively"""
        Mi = self.Mi
        yh = [Mi[i][0] * x[0] + Mi[i][1] * x[1] + Mi[i][2] * x[2] + Mi[i][3] for i in range(4)]
        y = [yh[i] / yh[3] for i in range(3)]
        f, gy = implicit(self.kind, self.pdec, y)
        # d y_i / d x_j = (Mi[i][j] - y_i Mi[3][j]) / yh_3
        gx = [sum(gy[i] * (Mi[i][j] - y[i] * Mi[3][j]) for i in range(3)) / yh[3] for j in range(3)]
        gn = norm(gx)
        if gn == 0:
            return None
        return abs(f) / gn


# ------------------------------------------------------------------------------------ report
class Worst:
    def __init__(self, name, limit):
        self.name, self.limit, self.val, self.where, self.count = name, limit, 0.0, "", 0

    def add(self, v, where):
        self.count += 1
        if v > self.val or (v != v):
            self.val, self.where = v, where

    def ok(self):
        return self.val <= self.limit

    def line(self):
        return "%-14s %9.2e (limit %.0e) %-4s %6d samples%s" % (
            self.name, self.val, self.limit, "ok" if self.ok() else "FAIL", self.count,
            ("  at " + self.where) if self.where and self.val > 0 else "")


# --------------------------------------------------------------------------- (1) exactness
def check_exact(surfs, shapes, W):
    # the size of each shape: the box of its tagged patches' control points (as rg2 check)
    box = {}
    for s in surfs:
        if s.tag is None:
            continue
        for P, t in zip(s.patches, s.tag):
            if t < 0:
                continue
            lo, hi = box.setdefault(t, ([math.inf] * 3, [-math.inf] * 3))
            for r in range(P.du + 1):
                for q in range(P.dv + 1):
                    x = P.point3(r, q)
                    for k in range(3):
                        lo[k], hi[k] = min(lo[k], x[k]), max(hi[k], x[k])
    ssize = {t: math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3))) for t, (lo, hi) in box.items()}
    per_shape = {}
    ts = [Fraction(k, RES_N) for k in range(RES_N + 1)]
    for si, s in enumerate(surfs):
        if s.tag is None:
            continue
        for pi, (P, t) in enumerate(zip(s.patches, s.tag)):
            if t < 0:
                continue
            sh = shapes[t]
            size = Decimal(ssize[t])
            worst = per_shape.setdefault(t, Worst("exact %s" % sh.label, LIMIT_EXACT))
            for u in ts:
                for v in ts:
                    r = sh.residual(eval_point(P, u, v))
                    if r is None:
                        continue
                    val = float(r / size)
                    worst.add(val, "surface %d patch (%d,%d) u=%s v=%s" % (si, pi // s.nv, pi % s.nv, u, v))
                    W.add(val, "%s: surface %d patch (%d,%d) u=%s v=%s" % (sh.label, si, pi // s.nv, pi % s.nv, u, v))
    return per_shape


# ----------------------------------------------------------------------------- (2) seams
def curv_parts(jet):
    x, xu, xv, xuu, xuv, xvv = jet
    n = cross(xu, xv)
    nn = norm(n)
    n = [c / nn for c in n]
    E, F, G = dot(xu, xu), dot(xu, xv), dot(xv, xv)
    e, f, g = dot(n, xuu), dot(n, xuv), dot(n, xvv)
    return n, (E, F, G), (e, f, g)


def normal_curvature(jet, parts, d):
    x, xu, xv = jet[0], jet[1], jet[2]
    n, (E, F, G), (e, f, g) = parts
    # d projected to the tangent plane, in parameter coordinates: [E F; F G] a = [xu.d, xv.d]
    r1, r2 = dot(xu, d), dot(xv, d)
    det = E * G - F * F
    a1 = (G * r1 - F * r2) / det
    a2 = (E * r2 - F * r1) / det
    return (e * a1 * a1 + 2 * f * a1 * a2 + g * a2 * a2) / (E * a1 * a1 + 2 * F * a1 * a2 + G * a2 * a2)


def principal_max(parts):
    n, (E, F, G), (e, f, g) = parts
    det = E * G - F * F
    K = (e * g - f * f) / det
    H = (e * G - 2 * f * F + g * E) / (2 * det)
    disc = H * H - K
    if disc < 0:
        disc = D0
    s = disc.sqrt()
    return max(abs(H + s), abs(H - s))


def degenerate(jet, size):
    xu, xv = jet[1], jet[2]
    a, b = norm(xu), norm(xv)
    tiny = Decimal(1e-9) * Decimal(size)
    if a < tiny or b < tiny:
        return True
    return norm(cross(xu, xv)) < Decimal(1e-9) * a * b


def limit_normal(jet, t):
    """the normal's limit at a collapsed side (Su = 0 there: n ~ (v - v0) Suv x Sv; Sv = 0:
    n ~ (u - u0) Su x Suv), the sign making it the limit of Su x Sv from inside the patch"""
    x, xu, xv, xuu, xuv, xvv = jet
    if norm(xu) < norm(xv):
        n = cross(xuv, xv)
    else:
        n = cross(xu, xuv)
    # inside the patch the parameter moves away from the collapsed side; which side that is
    # does not matter for the angle between two patches' limits taken the same way
    nn = norm(n)
    if nn == 0:
        return None
    return [c / nn for c in n]


def seam_list(s):
    """(L, R, direction) for every seam of a surface: along u, L (i, j) | R (i+1, j) meet at
    L's u = 1 and R's u = 0; along v likewise; closing seams of closed directions included"""
    out = []
    for i in range(s.nu if s.closed_u else s.nu - 1):
        for j in range(s.nv):
            out.append(((i, j), ((i + 1) % s.nu, j), "u"))
    for i in range(s.nu):
        for j in range(s.nv if s.closed_v else s.nv - 1):
            out.append(((i, j), (i, (j + 1) % s.nv), "v"))
    return out


def seam_point(s, L, R, dirn, t):
    if dirn == "u":
        return eval_jet(L, Fraction(1), t), eval_jet(R, Fraction(0), t)
    return eval_jet(L, t, Fraction(1)), eval_jet(R, t, Fraction(0))


def check_seams(surfs, W0, W1, W2, W1p, W2p, Wlim, counts):
    ts = [Fraction(k, SEAM_N) for k in range(SEAM_N + 1)]
    for si, s in enumerate(surfs):
        size = s.size
        dsize = Decimal(size)
        for (Li, Ri, dirn) in seam_list(s):
            L, R = s.patch(*Li), s.patch(*Ri)
            where0 = "surface %d %s seam (%d,%d)|(%d,%d)" % (si, dirn, Li[0], Li[1], Ri[0], Ri[1])
            for t in ts:
                jl, jr = seam_point(s, L, R, dirn, t)
                # the position gap, at the exact sample (a pole included)
                gap = norm([jl[0][k] - jr[0][k] for k in range(3)])
                W0.add(float(gap / dsize), "%s t=%s" % (where0, t))
                samples = [(t, jl, jr, W1, W2)]
                if degenerate(jl, size) or degenerate(jr, size):
                    counts["pole"] += 1
                    samples = []
                    # at the pole itself: the limit normals (paper section 5: the fan is G1 there)
                    la, lb = limit_normal(jl, t), limit_normal(jr, t)
                    if la is not None and lb is not None:
                        Wlim.add(math.atan2(float(norm(cross(la, lb))), float(dot(la, lb))), "%s t=%s" % (where0, t))
                    for step in POLE_STEPS:
                        tt = t + step if t == 0 else t - step
                        a, b = seam_point(s, L, R, dirn, tt)
                        if degenerate(a, size) or degenerate(b, size):
                            counts["unmeasured"] += 1
                            continue
                        samples.append((tt, a, b, W1p, W2p))
                for (tt, a, b, w1, w2) in samples:
                    where = "%s t=%s" % (where0, tt)
                    ang, jump = seam_gaps(a, b, dirn, dsize)
                    w1.add(ang, where)
                    w2.add(jump, where)
                    counts["measured"] += 1


def seam_gaps(a, b, dirn, dsize):
    """G1 and G2 between the jets a and b of the two sides of a seam along dirn: the angle
    between the normals and the largest jump of the normal curvature in six tangent directions
    relative to max(|k1|, |k2|, 1 / size)"""
    pa, pb = curv_parts(a), curv_parts(b)
    na, nb = pa[0], pb[0]
    ang = math.atan2(float(norm(cross(na, nb))), float(dot(na, nb)))
    # six tangent directions: e1 along the seam, e2 = n x e1, and combinations
    T = a[2] if dirn == "u" else a[1]
    tn = norm(T)
    e1 = [c / tn for c in T]
    e2 = cross(na, e1)
    dirs = [e1, e2]
    for (c1, c2) in ((1, 1), (1, -1), (1, 2), (2, -1)):
        dirs.append([c1 * e1[k] + c2 * e2[k] for k in range(3)])
    kscale = max(principal_max(pa), principal_max(pb), 1 / dsize)
    jump = max(abs(normal_curvature(a, pa, d) - normal_curvature(b, pb, d)) for d in dirs)
    return ang, float(jump / kscale)


# ------------------------------------------------------------------- (3) the construction
def curve_construct(P, w, b, g, closed, first_leg):
    """MATH.md section 1 on a polygon P of points (lists of Fractions): the segments' Bezier
    coefficients [b0, b1, b2, b3] and weights w_i, in order (closed: 0..n-1; open: 1..n-3)"""
    n = len(P)
    F = Fraction

    def W(i):   # weight of leg i
        return F(w[i % n]) if closed else F(w[i - first_leg])

    def J(i):   # junction i: (b_i, g_i)
        return (F(b[i % n]), F(g[i % n])) if closed else (F(b[i]), F(g[i]))

    def pt(i):
        return P[i % n] if closed else P[i]

    cache = {}

    def K(i):
        bi, gi = J(i)
        return 2 * bi * (3 * W(i) - 2) + 2 * bi * bi * (3 * W(i - 1) - 2) + gi

    def ts(i):
        if i not in cache:
            bi, _ = J(i)
            A = 2 * (W(i) + bi * W(i - 1)) / (W(i - 1) * K(i))
            b1, _ = J(i + 1)
            B = 2 * b1 * b1 * (W(i + 1) + b1 * W(i)) / (W(i + 1) * K(i + 1))
            Lr = 1 / (1 + A + B)
            cache[i] = (A * Lr, B * Lr)
        return cache[i]

    def x(i):
        bi, _ = J(i)
        return W(i) / (W(i) + bi * W(i - 1))

    def lerp(p, q, a):   # (1 - a) p + a q
        return [pk + a * (qk - pk) for pk, qk in zip(p, q)]

    def bb1(i):
        t, _ = ts(i)
        return lerp(pt(i), pt(i + 1), t)

    def bb2(i):
        _, s = ts(i)
        return lerp(pt(i + 1), pt(i), s)

    def bb0(i):
        return lerp(bb2(i - 1), bb1(i), x(i))

    segs = range(n) if closed else range(1, n - 2)
    out = []
    for i in segs:
        out.append(([bb0(i), bb1(i), bb2(i), bb0(i + 1)], W(i)))
    return out


def rat_point(du, dv, net, u, v):
    """the 3D point of a rational patch at (u, v), exactly (Fractions)"""
    acc = [Fraction(0)] * 4
    for r in range(du + 1):
        br = binom(du, r) * u ** r * (1 - u) ** (du - r)
        for q in range(dv + 1):
            bq = br * binom(dv, q) * v ** q * (1 - v) ** (dv - q)
            h = net(r, q)
            for k in range(4):
                acc[k] += bq * h[k]
    return [acc[k] / acc[3] for k in range(3)]


def check_construction(surfs, mesh_js, Wb, counts):
    for si, (s, m) in enumerate(zip(surfs, mesh_js)):
        F = Fraction
        nu, nv = m["nu"], m["nv"]
        p = [[[F(m["W"][i][j]) * F(c) for c in m["d"][i][j]] + [F(m["W"][i][j])] for j in range(nv)]
             for i in range(nu)]
        mu, mv = m["u"], m["v"]
        rows = [curve_construct([p[i][j] for i in range(nu)], mu["w"], mu["b"], mu["g"], mu["closed"],
                                mu["first_leg"]) for j in range(nv)]
        nsu = len(rows[0])
        # cols[I][r] = the v-construction of column r of u-segment I
        out = {}
        for I in range(nsu):
            wu = rows[0][I][1]
            ou = (F(1), wu, wu, F(1))
            for r in range(4):
                col = curve_construct([rows[j][I][0][r] for j in range(nv)], mv["w"], mv["b"], mv["g"],
                                      mv["closed"], mv["first_leg"])
                for J, (bs, wv) in enumerate(col):
                    ov = (F(1), wv, wv, F(1))
                    net = out.setdefault((I, J), [[None] * 4 for _ in range(4)])
                    for q in range(4):
                        net[r][q] = [ou[r] * ov[q] * c for c in bs[q]]
        nsv = len(out) // nsu
        if nsu != s.nu:
            counts["build_skipped"] += 1
            continue

        def diff(I, J, off):
            P = s.patch(I, J + off)
            H = out[I, J]
            n = P.dv + 1
            if (P.du, P.dv) == (3, 3):
                big = max(abs(x) for x in P.raw)
                worst = 0.0
                for r in range(4):
                    for q in range(4):
                        for k in range(4):
                            d = abs(Fraction(P.raw[4 * (r * n + q) + k]) - H[r][q][k])
                            worst = max(worst, float(d) / big)
                return worst
            # a patch of a higher degree (a general-quadratic cap's surface stores its body as
            # D H, D the arc's quadratic denominator: docs/poles.md) is the same rational
            # patch: compared by its points, exactly, at 5 x 5 parameters, relative to the
            # box of its control points
            pts = [P.point3(r, q) for r in range(P.du + 1) for q in range(P.dv + 1)]
            big = math.sqrt(sum((max(x[k] for x in pts) - min(x[k] for x in pts)) ** 2 for k in range(3)))
            worst = 0.0
            for a in range(5):
                for b in range(5):
                    u, v = Fraction(a, 4), Fraction(b, 4)
                    x1 = rat_point(P.du, P.dv, lambda r, q: [Fraction(c) for c in P.raw[4 * (r * n + q):4 * (r * n + q) + 4]], u, v)
                    x2 = rat_point(3, 3, lambda r, q: H[r][q], u, v)
                    worst = max(worst, float(max(abs(x1[k] - x2[k]) for k in range(3))) / big)
            return worst

        # the body's first row among the surface's (caps add rows before and after it)
        offs = range(0, s.nv - nsv + 1)
        off = min(offs, key=lambda o: diff(0, 0, o)) if len(offs) > 1 else 0
        for I in range(nsu):
            for J in range(nsv):
                Wb.add(diff(I, J, off), "surface %d patch (%d,%d)" % (si, I, J + off))
                counts["built"] += 1


def check_collapsed(surfs, Wc, counts):
    """a patch side whose control points lie within 1e-9 of the size of each other is a
    collapsed side (a pole, an apex): its points, exactly, must be one point to rounding"""
    for si, s in enumerate(surfs):
        for pi, P in enumerate(s.patches):
            n = P.dv + 1
            sides = (("u=0", [(0, q) for q in range(n)]), ("u=1", [(P.du, q) for q in range(n)]),
                     ("v=0", [(r, 0) for r in range(P.du + 1)]), ("v=1", [(r, P.dv) for r in range(P.du + 1)]))
            for name, idx in sides:
                pts = [P.point3(r, q) for r, q in idx]
                spread = max(math.dist(pts[0], x) for x in pts)
                if spread > 1e-9 * s.size:
                    continue
                ex = []
                for r, q in idx:
                    h = [Fraction(c) for c in P.raw[4 * (r * n + q):4 * (r * n + q) + 4]]
                    ex.append([h[k] / h[3] for k in range(3)])
                d = max(math.sqrt(float(sum((x[k] - ex[0][k]) ** 2 for k in range(3)))) for x in ex)
                Wc.add(d / s.size, "surface %d patch (%d,%d) side %s" % (si, pi // s.nv, pi % s.nv, name))
                counts["collapsed"] += 1


def elevate(H, du, dv, Du, Dv):
    """exact degree elevation of a net H[r][s][k] (Fractions) from (du, dv) to (Du, Dv)"""
    def elev1(pts, d, D):
        while d < D:
            pts = [[(Fraction(i, d + 1) * (pts[i - 1][k] if i > 0 else 0)
                     + Fraction(d + 1 - i, d + 1) * (pts[i][k] if i <= d else 0)) for k in range(4)]
                   for i in range(d + 2)]
            d += 1
        return pts
    rows = [elev1(H[r], dv, Dv) for r in range(du + 1)]
    cols = [elev1([rows[r][q] for r in range(du + 1)], du, Du) for q in range(Dv + 1)]
    return [[cols[q][r] for q in range(Dv + 1)] for r in range(Du + 1)]


def check_exports(surfs, bvf, bezf, Wx, counts):
    """the BezierView (.bv) and geomview (.bez) files of the same build hold the dump's patches:
    .bv bit for bit; .bez, whose patches are raised to one degree for the whole file, within one
    rounding of the exact elevation of the dump's patch (relative to its largest coordinate)"""
    with open(bvf) as f:
        toks = f.read().split()
    k = 0
    for si, s in enumerate(surfs):
        if toks[k] != "Group":
            raise ValueError("%s: no Group line for surface %d" % (bvf, si))
        k += 3
        for pi, P in enumerate(s.patches):
            if toks[k] != "8" or (int(toks[k + 1]), int(toks[k + 2])) != (P.du, P.dv):
                raise ValueError("%s: surface %d patch %d: type or degrees differ" % (bvf, si, pi))
            k += 3
            n = 4 * (P.du + 1) * (P.dv + 1)
            vals = [float(x) for x in toks[k:k + n]]
            k += n
            if vals != P.raw:
                big = max(abs(x) for x in P.raw)
                Wx.add(max(abs(a - b) for a, b in zip(vals, P.raw)) / big, ".bv surface %d patch %d" % (si, pi))
            else:
                Wx.add(0.0, "")
            counts["exported"] += 1
    with open(bezf) as f:
        toks = f.read().split()
    Du, Dv = int(toks[0][3]), int(toks[0][4])
    k = 1
    for si, s in enumerate(surfs):
        for pi, P in enumerate(s.patches):
            n = 4 * (Du + 1) * (Dv + 1)
            vals = [float(x) for x in toks[k:k + n]]
            k += n
            # u fastest: vertex (r, q) at 4 (q (Du + 1) + r)
            got = [[vals[4 * (q * (Du + 1) + r):4 * (q * (Du + 1) + r) + 4] for q in range(Dv + 1)] for r in range(Du + 1)]
            m = P.dv + 1
            H = [[[Fraction(c) for c in P.raw[4 * (r * m + q):4 * (r * m + q) + 4]] for q in range(P.dv + 1)]
                 for r in range(P.du + 1)]
            if (P.du, P.dv) != (Du, Dv):
                H = elevate(H, P.du, P.dv, Du, Dv)
            big = max(abs(x) for x in P.raw)
            err = max(abs(float(Fraction(got[r][q][c]) - H[r][q][c])) for r in range(Du + 1)
                      for q in range(Dv + 1) for c in range(4)) / big
            Wx.add(err, ".bez surface %d patch %d" % (si, pi))
    if k != len(toks):
        raise ValueError("%s: %d numbers left over" % (bezf, len(toks) - k))


def blossom_row(P, U, k, args):
    """the blossom of the cubic B-spline with de Boor points P (lists of Fractions) and knots U
    at args (3 values), on the span [U_k, U_k+1]: de Boor's algorithm with one argument per
    level (standard B-spline theory, not MATH.md's construction)"""
    d = {i: P[i] for i in range(k - 3, k + 1)}
    for r in range(1, 4):
        x = args[r - 1]
        for i in range(k, k - 4 + r, -1):
            a = (x - U[i]) / (U[i + 4 - r] - U[i])
            d[i] = [(1 - a) * p + a * q for p, q in zip(d[i - 1], d[i])]
    return d[k]


def nurbs_bezier(js):
    """the rational Bezier patches of a design's bi-cubic NURBS (the nurbs operation's points,
    weights and knots read as the doubles rg2 reads), by blossoming, exactly: {(a, b): net}"""
    F = lambda x: Fraction(float(x))
    nu, nv = js["nu"], js["nv"]
    pts, ws = js["points"], js.get("weights", [1] * (nu * nv))
    U, V = [F(x) for x in js["knots_u"]], [F(x) for x in js["knots_v"]]
    H = [[[F(ws[i * nv + j]) * F(c) for c in pts[i * nv + j]] + [F(ws[i * nv + j])] for j in range(nv)]
         for i in range(nu)]
    out = {}
    for a in range(3, nu):            # u spans [U_a, U_a+1]
        ua = [(U[a], U[a], U[a]), (U[a], U[a], U[a + 1]), (U[a], U[a + 1], U[a + 1]), (U[a + 1],) * 3]
        rows = [[blossom_row([H[i][j] for i in range(nu)], U, a, ua[r]) for j in range(nv)] for r in range(4)]
        for b in range(3, nv):
            vb = [(V[b], V[b], V[b]), (V[b], V[b], V[b + 1]), (V[b], V[b + 1], V[b + 1]), (V[b + 1],) * 3]
            out[a - 3, b - 3] = [[blossom_row(rows[r], V, b, vb[q]) for q in range(4)] for r in range(4)]
    return out


def check_nurbs(design, surfs, Wn, counts):
    """every NURBS of the design, its Bezier patches by blossoming against the built patches:
    a NURBS patch the build kept (the wall between the seams) must be one of them to rounding"""
    for name, op in design["meshes"].items():
        if "nurbs" not in op:
            continue
        for key, net in nurbs_bezier(op["nurbs"]).items():
            best, where = None, ""
            for si, s in enumerate(surfs):
                for pi, P in enumerate(s.patches):
                    if (P.du, P.dv) != (3, 3):
                        continue
                    big = max(abs(x) for x in P.raw)
                    # the homogeneous nets of a polynomial-mode mesh are the same up to rounding
                    # (weights (1, 1, 1, 1) per segment): compared coordinate by coordinate
                    d = max(abs(Fraction(P.raw[4 * (r * 4 + q) + k]) - net[r][q][k])
                            for r in range(4) for q in range(4) for k in range(4))
                    e = float(d) / big
                    if best is None or e < best:
                        best, where = e, "meshes.%s interval (%d,%d) = surface %d patch (%d,%d)" % (
                            name, key[0], key[1], si, pi // s.nv, pi % s.nv)
            counts["nurbs_intervals"] += 1
            if best is not None and best < 1e-6:
                Wn.add(best, where)
                counts["nurbs_matched"] += 1


def rat_curve_jet(bs, w, t):
    """f, f', f'' of the rational cubic with affine coefficients bs and weights (1, w, w, 1) at
    t, exactly, by the quotient rule on its numerator and denominator"""
    om = (Fraction(1), w, w, Fraction(1))
    B = [binom(3, k) * t ** k * (1 - t) ** (3 - k) for k in range(4)]
    B1 = [3 * ((binom(2, k - 1) * t ** (k - 1) * (1 - t) ** (3 - k) if k >= 1 else 0)
               - (binom(2, k) * t ** k * (1 - t) ** (2 - k) if k <= 2 else 0)) for k in range(4)]
    B2 = [6 * ((t ** (k - 2) * (1 - t) ** (3 - k) * binom(1, k - 2) if 2 <= k <= 3 else 0)
               - 2 * (t ** (k - 1) * (1 - t) ** (2 - k) * binom(1, k - 1) if 1 <= k <= 2 else 0)
               + (t ** k * (1 - t) ** (1 - k) * binom(1, k) if k <= 1 else 0)) for k in range(4)]
    dim = len(bs[0])
    N = [[sum(Bx[k] * om[k] * bs[k][c] for k in range(4)) for c in range(dim)] for Bx in (B, B1, B2)]
    D = [sum(Bx[k] * om[k] for k in range(4)) for Bx in (B, B1, B2)]
    f = [N[0][c] / D[0] for c in range(dim)]
    f1 = [(N[1][c] - f[c] * D[1]) / D[0] for c in range(dim)]
    f2 = [(N[2][c] - 2 * f1[c] * D[1] - f[c] * D[2]) / D[0] for c in range(dim)]
    return f, f1, f2


def check_math(counts):
    """MATH.md sections 1 and 2 proved on exact rational data (no rounding anywhere): (a) the
    construction gives G2 (Definition 1) at every junction of random closed and open polygons in
    R^4 with random weights and scalars; (b) an open arc partition (rational half-angle tangents,
    so every sine and cosine is rational) is reproduced exactly: each produced segment is the
    degree-raised conic of its arc, control point for control point, and lies on the circle.
    Returns a list of failures."""
    import random
    rnd = random.Random(2011)
    F = Fraction
    fails = []

    def rf(lo, hi):
        return F(rnd.randint(int(lo * 1000), int(hi * 1000)), 1000)

    for closed in (True, False):
        for trial in range(3):
            n = 7
            P = [[rf(-2, 2) for _ in range(3)] + [rf(0.5, 2)] for _ in range(n)]
            nw = n if closed else n + 1
            w = [rf(0.4, 2) for _ in range(nw)]
            b = [rf(0.5, 2) for _ in range(n)]
            first = 0 if closed else -1
            g = []
            for i in range(n):
                wi = w[i % n] if closed else w[i + 1]
                wm = w[(i - 1) % n] if closed else w[i]
                base = 2 * b[i] * (3 * wi - 2) + 2 * b[i] ** 2 * (3 * wm - 2)
                g.append(max(rf(-1, 1), -base + rf(0.1, 1)))      # K_i > 0
            segs = curve_construct(P, w, b, g, closed, first)
            idx = list(range(n)) if closed else list(range(1, n - 2))
            for k in range(1, len(segs)) if not closed else range(len(segs)):
                (bl, wl), (br, wr) = segs[k - 1], segs[k]
                i = idx[k]
                fl = rat_curve_jet(bl, wl, F(1))
                fr = rat_curve_jet(br, wr, F(0))
                bi, gi = F(b[i % n]), F(g[i % n])
                ok = (fl[0] == fr[0] and all(fr[1][c] == bi * fl[1][c] for c in range(4))
                      and all(fr[2][c] == bi * bi * fl[2][c] + gi * fl[1][c] for c in range(4)))
                counts["math_junctions"] += 1
                if not ok:
                    fails.append("G2 (Definition 1) fails at junction %d of a %s polygon" % (i, "closed" if closed else "open"))

    # (b) an open partition: n points, arcs -1..n-1
    n = 8
    tans = [F(rnd.randint(5, 60), 100) for _ in range(n + 1)]     # tan(beta / 2): beta in (0.1, 1.08)
    cs = [((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)) for t in tans]      # (cos beta, sin beta)

    def rot(p, c, s):
        return (c * p[0] - s * p[1], s * p[0] + c * p[1])
    start = (F(1), F(0))
    arcs = []
    for (c, s) in cs:
        mid = rot(start, c, s)
        end = rot(mid, c, s)
        Pm = (mid[0] / c, mid[1] / c)
        b1 = tuple((start[k] + 2 * c * Pm[k]) / (1 + 2 * c) for k in range(2))
        b2 = tuple((2 * c * Pm[k] + end[k]) / (1 + 2 * c) for k in range(2))
        arcs.append((start, b1, b2, end, (1 + 2 * c) / 3))
        start = end

    def meet(a1, a2, c1, c2):
        # line a1 a2 with line c1 c2
        d1 = (a2[0] - a1[0], a2[1] - a1[1])
        d2 = (c2[0] - c1[0], c2[1] - c1[1])
        den = d1[0] * d2[1] - d1[1] * d2[0]
        lam = ((c1[0] - a1[0]) * d2[1] - (c1[1] - a1[1]) * d2[0]) / den
        return (a1[0] + lam * d1[0], a1[1] + lam * d1[1])
    # arc list index a = arc a - 1 (arcs -1..n-1); junction i lies between arc i-1 and arc i
    pts = [list(meet(arcs[i][1], arcs[i][2], arcs[i + 1][1], arcs[i + 1][2])) + [F(1)] for i in range(n)]
    w = [(1 + 2 * c) / 3 for (c, s) in cs]
    bsc = [cs[i + 1][1] / cs[i][1] for i in range(n)]
    gsc = [2 * bsc[i] * (1 - cs[i + 1][0]) + 2 * bsc[i] ** 2 * (1 - cs[i][0]) for i in range(n)]
    segs = curve_construct(pts, w, bsc, gsc, False, -1)
    for k, (bs, wi) in enumerate(segs):
        i = k + 1                                   # segment i is arc i
        a = arcs[i + 1]
        same = wi == a[4] and all(bs[r][0] == a[r][0] and bs[r][1] == a[r][1] and bs[r][2] == 1 for r in range(4))
        on = all((lambda f: f[0] ** 2 + f[1] ** 2 == 1)(rat_curve_jet([x[:2] for x in bs], wi, F(j, 7))[0])
                 for j in range(8))
        counts["math_arcs"] += 1
        if not (same and on):
            fails.append("arc %d of an open partition is not reproduced (same points %s, on the circle %s)" % (i, same, on))
    # (c) eq. (13): the polar knots collapse the sphere's end rows to (0, 0, Zs, 1), (0, 0, Zn, 1)
    def blossom(coefs, a, b, c):     # coefs of 1, v, v^2 (a quadratic as a cubic)
        return coefs[0] + coefs[1] * (a + b + c) / 3 + coefs[2] * (a * b + a * c + b * c) / 3
    sphere = [(0, 2, -2), (0, 2, -2), (-1, 2, 0), (1, -2, 2)]    # 2v(1-v) cu, 2v(1-v) su, 2v-1, 2v^2-2v+1
    for trial in range(4):
        v1 = F(rnd.randint(5, 45), 100)
        vm = F(rnd.randint(55, 95), 100)
        vmm1 = v1 / (v1 - 1)
        south = [blossom([F(c) for c in co], vmm1, F(0), v1) for co in sphere]
        north = [blossom([F(c) for c in co], vm, F(1), 1 / vm) for co in sphere]
        Zs = (3 - 3 * v1 + 2 * v1 * v1) / (3 * (v1 - 1))
        Zn = (2 - vm + 2 * vm * vm) / (3 * vm)
        ok = (south == [0, 0, Zs, 1] and north == [0, 0, Zn, 1]
              and (v1 - 0) / (0 - vmm1) == 1 - v1 and (1 / vm - 1) / (1 - vm) == 1 / vm)
        counts["math_poles"] += 1
        if not ok:
            fails.append("eq. (13) fails for v_1 = %s, v_m = %s" % (v1, vm))
    return fails


def check_polar_points(design, mesh_js, shapes, Wz, counts):
    """a design's polar mesh of a sphere, output as it is: its first and last rows are the points
    of eq. (13) from its knots, placed by the shape's matrix (to rounding)"""
    meshes = design["meshes"]
    outs = design.get("output")
    outs = [outs] if isinstance(outs, str) else (outs or [list(meshes)[-1]])
    by_label = {sh.label: sh for sh in shapes}
    for k, name in enumerate(outs):
        op = meshes.get(name, {})
        sh = by_label.get(op.get("polar"))
        if sh is None or sh.kind != "sphere" or k >= len(mesh_js) or "knots" not in op.get("v", {}):
            continue
        kn = [Fraction(float(x)) for x in op["v"]["knots"]]
        v1, vm = kn[0], kn[-1]
        rho = Fraction(sh.params["radius"])
        Zs = (3 - 3 * v1 + 2 * v1 * v1) / (3 * (v1 - 1))
        Zn = (2 - vm + 2 * vm * vm) / (3 * vm)
        m = mesh_js[k]
        size = math.dist(*[[float(x) for x in m["d"][0][j]] for j in (0, -1)])
        for j, Z in ((0, Zs), (m["nv"] - 1, Zn)):
            q = [sum(sh.M[r][c] * x for c, x in enumerate((0, 0, rho * Z, 1))) for r in range(4)]
            want = [q[r] / q[3] for r in range(3)]
            for i in range(m["nu"]):
                got = [Fraction(x) for x in m["d"][i][j]]
                Wz.add(math.sqrt(float(sum((got[r] - want[r]) ** 2 for r in range(3)))) / size,
                       "meshes.%s point [%d, %d]" % (name, i, j))
            counts["polar_points"] += 1


def affine_ok(h, p3, w):
    """whether a CAD file's control point (p3, weight w), written as an affine point and a
    weight, is the dump's homogeneous h: w the same double, each coordinate h_k / h_w correctly
    rounded (the nearest double to the exact quotient). Returns the error in units of the last
    place (0 when so)."""
    if w != h[3]:
        return math.inf
    worst = 0.0
    for k in range(3):
        want = float(Fraction(h[k]) / Fraction(h[3]))     # correctly rounded
        if p3[k] != want:
            worst = max(worst, abs(p3[k] - want) / math.ulp(want if want else 1e-300))
    return worst


def patch_sides(P):
    """the four sides of patch P: (name, [(r, q) of its control points])"""
    return (("u=0", [(0, q) for q in range(P.dv + 1)]), ("u=1", [(P.du, q) for q in range(P.dv + 1)]),
            ("v=0", [(r, 0) for r in range(P.du + 1)]), ("v=1", [(r, P.dv) for r in range(P.du + 1)]))


def collapsed_sides(s, P):
    """the names of P's sides whose points h / w lie within 1e-9 of the size of each other (as
    check_collapsed: a pole, an apex)"""
    out = set()
    for name, idx in patch_sides(P):
        pts = [P.point3(r, q) for r, q in idx]
        if max(math.dist(pts[0], x) for x in pts) <= 1e-9 * s.size:
            out.add(name)
    return out


def judge_cad(fmt, si, s, pi, P, pts, W):
    """one patch of a CAD file, pts[(r, q)] = (affine point, weight): every weight the dump's;
    every coordinate the correctly rounded h_k / h_w (0 ulp), or, on a side the file writes as
    one point bit for bit (a pole), within SNAP_ROUNDINGS roundings of the surface's largest
    coordinate of it, times the ratio of the largest weight to the smallest among the patch's
    one-point sides' points (at least 1); every side collapsed in the dump written as one point.
    Returns the one-point sides' points (for the poles' check across patches)."""
    Wc, Wsnap, Wone = W
    where = "%s surface %d patch (%d,%d)" % (fmt, si, pi // s.nv, pi % s.nv)
    coll = collapsed_sides(s, P)
    one, at = set(), []
    for name, idx in patch_sides(P):
        written = {tuple(pts[x][0]) for x in idx}
        if len(written) == 1:
            one.update(idx)
            at.append(written.pop())
        if name in coll:
            Wone.add(len({tuple(pts[x][0]) for x in idx}) - 1, "%s side %s" % (where, name))
    n = P.dv + 1
    rounding = sys.float_info.epsilon * s.big
    # the writers' tolerance grows with the weights' ratio of a pole's points (here: of this
    # patch's one-point sides' points)
    ws = [abs(P.raw[4 * (r * n + q) + 3]) for (r, q) in one]
    ratio = max(ws) / min(ws) if ws and min(ws) > 0 else 1.0
    rounding *= ratio if ratio > 1.0 and math.isfinite(ratio) else 1.0
    for (r, q), (p3, w) in sorted(pts.items()):
        h = P.raw[4 * (r * n + q):4 * (r * n + q) + 4]
        e = affine_ok(h, p3, w)
        if e and w == h[3] and (r, q) in one:
            ex = [Fraction(h[k]) / Fraction(h[3]) for k in range(3)]
            Wsnap.add(max(abs(float(Fraction(p3[k]) - ex[k])) for k in range(3)) / rounding,
                      "%s point [%d][%d]" % (where, r, q))
            e = 0.0
        Wc.add(e, "%s point [%d][%d]" % (where, r, q))
    return at


def check_cad(surfs, stepf, igsf, W, counts):
    """the STEP (face per patch) and IGES (entity 128 per patch) files of the same build: each
    patch's control points as affine points and weights (the form both standards store), judged
    by judge_cad; the poles one point across the patches around them (Wone: the points a pole is
    written as, less 1) and the IGES points the STEP ones bit for bit (Wsame: how many differ).
    Returns the STEP file's points, {(surface, patch): {(r, q): (point, weight)}}."""
    import re
    Wc, Wsnap, Wone, Wsame = W
    patches = [(si, pi, P) for si, s in enumerate(surfs) for pi, P in enumerate(s.patches)]
    poles = {}                           # (format, surface) -> the one-point sides' points

    def judge(fmt, si, pi, P, pts):
        poles.setdefault((fmt, si), []).extend(judge_cad(fmt, si, surfs[si], pi, P, pts, (Wc, Wsnap, Wone)))
        counts["cad"] += 1

    with open(stepf) as f:
        text = f.read()
    pts = {int(m.group(1)): [float(x) for x in m.group(2).split(",")]
           for m in re.finditer(r"#(\d+)=CARTESIAN_POINT\('',\(([^)]*)\)\);", text)}
    surf_re = re.compile(r"B_SPLINE_SURFACE\((\d+),(\d+),\((.*?)\),\.[A-Z_]+\.,.*?"
                         r"RATIONAL_B_SPLINE_SURFACE\(\((.*?)\)\)\s*REPRESENTATION_ITEM", re.S)
    found = list(surf_re.finditer(text))
    if len(found) != len(patches):
        raise ValueError("%s: %d rational surfaces for %d patches" % (stepf, len(found), len(patches)))
    step = {}
    for m, (si, pi, P) in zip(found, patches):
        du, dv = int(m.group(1)), int(m.group(2))
        refs = [[int(x) for x in re.findall(r"#(\d+)", row)] for row in re.findall(r"\(([^()]*)\)", m.group(3))]
        ws = [[float(x) for x in row.split(",")] for row in re.findall(r"\(([^()]*)\)", m.group(4))]
        if (du, dv) != (P.du, P.dv) or len(refs) != du + 1 or any(len(r) != dv + 1 for r in refs):
            raise ValueError("%s: surface %d patch %d: degrees or net differ" % (stepf, si, pi))
        step[si, pi] = {(r, q): (pts[refs[r][q]], ws[r][q]) for r in range(du + 1) for q in range(dv + 1)}
        judge("STEP", si, pi, P, step[si, pi])
    # IGES: the parameter section, columns 1-64, each entity's records by its directory pointer
    params = {}
    with open(igsf) as f:
        for line in f:
            if len(line) >= 73 and line[72] == "P":
                params.setdefault(int(line[64:72]), []).append(line[:64])
    ents = [("".join(v)).replace("D", "E") for k, v in sorted(params.items())]
    ents = [e for e in ents if e.startswith("128,")]
    if len(ents) != len(patches):
        raise ValueError("%s: %d entities 128 for %d patches" % (igsf, len(ents), len(patches)))
    for e, (si, pi, P) in zip(ents, patches):
        v = e.split(";")[0].split(",")
        K1, K2, M1, M2 = (int(x) for x in v[1:5])
        k = 10 + (K1 + M1 + 2) + (K2 + M2 + 2)
        nw = (K1 + 1) * (K2 + 1)
        ws = [float(x) for x in v[k:k + nw]]
        xyz = [float(x) for x in v[k + nw:k + 4 * nw]]
        if (K1, K2) != (P.du, P.dv):
            raise ValueError("%s: surface %d patch %d: degrees differ" % (igsf, si, pi))
        # the first index (u) runs fastest
        got = {(r, q): (xyz[3 * (q * (K1 + 1) + r):3 * (q * (K1 + 1) + r) + 3], ws[q * (K1 + 1) + r])
               for q in range(K2 + 1) for r in range(K1 + 1)}
        judge("IGES", si, pi, P, got)
        Wsame.add(sum(got[x][0] != step[si, pi][x][0] for x in got),
                  "IGES surface %d patch (%d,%d)" % (si, pi // surfs[si].nv, pi % surfs[si].nv))
    # a pole: the same point in every patch around it
    for (fmt, si), at in sorted(poles.items()):
        size = surfs[si].size
        groups = []
        for x in at:
            for g in groups:
                if math.dist(g[0], x) <= 1e-12 * size:
                    g.append(x)
                    break
            else:
                groups.append([x])
        for g in groups:
            Wone.add(len(set(g)) - 1, "%s surface %d pole at (%.6g, %.6g, %.6g)" % ((fmt, si) + tuple(g[0])))
    return step


def file_patch(P, pts):
    """patch P as a file holds it, pts[(r, q)] = (affine point, weight): control point (r, q) the
    exact homogeneous point (w x, w y, w z, w) (50 digits hold the products of two doubles)"""
    Q = Patch(P.du, P.dv, P.raw)
    Q.H = [[[dec(Fraction(pts[r, q][0][k]) * Fraction(pts[r, q][1])) for k in range(3)] + [dec(pts[r, q][1])]
            for q in range(P.dv + 1)] for r in range(P.du + 1)]
    return Q


def quotient_points(P):
    """P's control points as the writers wrote them before a collapsed row was one point: each
    h / w correctly rounded on its own, and the weight"""
    n = P.dv + 1
    out = {}
    for r in range(P.du + 1):
        for q in range(n):
            h = P.raw[4 * (r * n + q):4 * (r * n + q) + 4]
            out[r, q] = ([float(Fraction(h[k]) / Fraction(h[3])) for k in range(3)], h[3])
    return out


def near_pole_gaps(s, patch):
    """the worst G1 and G2 at each distance eps of POLE_EPS from the poles of surface s (the seam
    ends on a side collapsed in the dump), the patches patch(i, j): {eps: [G1, G2]}, or None when
    s has no pole"""
    worst = {}
    coll = [collapsed_sides(s, P) for P in s.patches]
    for (Li, Ri, dirn) in seam_list(s):
        for t, side in ((Fraction(0), "v=0" if dirn == "u" else "u=0"), (Fraction(1), "v=1" if dirn == "u" else "u=1")):
            if side not in coll[Li[0] * s.nv + Li[1]] and side not in coll[Ri[0] * s.nv + Ri[1]]:
                continue
            L, R = patch(*Li), patch(*Ri)
            for eps in POLE_EPS:
                a, b = seam_point(s, L, R, dirn, t + eps if t == 0 else t - eps)
                g = seam_gaps(a, b, dirn, Decimal(s.size))
                w = worst.setdefault(eps, [0.0, 0.0])
                w[0], w[1] = max(w[0], g[0]), max(w[1], g[1])
    return worst or None


def check_cad_poles(surfs, step, W1, W2, notes):
    """G1 and G2 next to the poles measured on the doubles of the STEP file (the IGES file's are
    the same, check_cad) 1/100, 1e-4 and 1e-6 from the pole: G1 within its limit at each (the
    limit normals agree to about 1e-13 and a collapsed row is one point), G2 times eps / (1/100)
    within G2's limit (it grows as 1 / eps from the limit normals' difference, no faster); and,
    for the notes, the same with each point h / w rounded on its own (as written before)"""
    for si, s in enumerate(surfs):
        nv = s.nv
        got = near_pole_gaps(s, lambda i, j: file_patch(s.patch(i, j), step[si, i * nv + j]))
        if not got:
            continue
        before = near_pole_gaps(s, lambda i, j: file_patch(s.patch(i, j), quotient_points(s.patch(i, j))))
        for eps, (g1, g2) in got.items():
            W1.add(g1, "surface %d eps %s" % (si, eps))
            W2.add(g2 * float(eps * 100), "surface %d eps %s" % (si, eps))
        notes.append("surface %d next to its poles, on the STEP/IGES doubles: %s; with each point h / w rounded on "
                     "its own: %s" % (si, "; ".join("eps %s G1 %.2g rad, G2 %.2g" % ((eps,) + tuple(got[eps]))
                                                     for eps in POLE_EPS),
                                      "; ".join("eps %s G1 %.2g rad, G2 %.2g" % ((eps,) + tuple(before[eps]))
                                                for eps in POLE_EPS)))


# --------------------------------------------------------------------------- (4) placement
def rot(axis, deg):
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    C = 1 - c
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s, 0],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s, 0],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C, 0],
            [0, 0, 0, 1]]


def placement(js):
    """the 4x4 matrix of a placement (docs/design-format.md: scale, rotate, translate, matrix),
    in floats"""
    M = [[float(i == j) for j in range(4)] for i in range(4)]

    def mm(A, B):
        return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
    if "scale" in js:
        sc = js["scale"]
        sc = [sc] * 3 if not isinstance(sc, list) else sc
        M = mm([[sc[0], 0, 0, 0], [0, sc[1], 0, 0], [0, 0, sc[2], 0], [0, 0, 0, 1]], M)
    if "rotate" in js:
        rs = js["rotate"] if isinstance(js["rotate"], list) else [js["rotate"]]
        for r in rs:
            M = mm(rot(r["axis"], r["degrees"]), M)
    if "translate" in js:
        t = js["translate"]
        M = mm([[1, 0, 0, t[0]], [0, 1, 0, t[1]], [0, 0, 1, t[2]], [0, 0, 0, 1]], M)
    if "matrix" in js:
        m = js["matrix"]
        M = mm([[m[4 * i + j] for j in range(4)] for i in range(4)], M)
    return M


def check_placement(design, shapes, Wp, counts, notes):
    dshapes = design["shapes"]
    by_label = {sh.label: sh for sh in shapes}
    for label, js in dshapes.items():
        if label not in by_label:
            continue
        M = placement(js)
        got = by_label[label].M
        scale = max(abs(M[i][j]) for i in range(4) for j in range(4))
        err = max(abs(float(got[i][j]) - M[i][j]) for i in range(4) for j in range(4)) / scale
        Wp.add(err, "shapes.%s" % label)
        counts["placed"] += 1
    # shapes made by operations: "<label>@meshes.<op>": the same quadric moved by the
    # operation's translate (transform) or not moved at all (mobius about that sphere)
    meshes = design["meshes"]
    for sh in shapes:
        if "@" not in sh.label:
            continue
        parent_label, opname = sh.label.rsplit("@meshes.", 1)
        parent = by_label.get(parent_label)
        op = meshes.get(opname, {})
        if parent is None or quadric(sh.kind, sh.params) is None:
            continue
        if "transform" in op:
            if any(k in op for k in ("rotate", "scale", "matrix")):
                notes.append("%s: a transform other than a translate is not re-derived" % sh.label)
                continue
            t = op.get("translate", [0, 0, 0])
            T = [[Fraction(int(i == j)) for j in range(4)] for i in range(4)]
            for k in range(3):
                T[k][3] = Fraction(t[k])
            want = mat_mul(T, parent.M)
        elif "mobius" in op:
            want = parent.M
        else:
            continue
        # the quadric of each: Q' = M^-T Q M^-1, compared up to a factor
        Q = quadric(sh.kind, sh.params)
        Qg = mat_mul(transpose(sh.Minv), mat_mul(Q, sh.Minv))
        Qw = mat_mul(transpose(mat_inv(want)), mat_mul(quadric(parent.kind, parent.params), mat_inv(want)))
        ig, jg = max(((i, j) for i in range(4) for j in range(4)), key=lambda ij: abs(Qw[ij[0]][ij[1]]))
        f = Qg[ig][jg] / Qw[ig][jg]
        big = max(abs(Qw[i][j]) for i in range(4) for j in range(4))
        err = max(abs(float(Qg[i][j] / f - Qw[i][j])) for i in range(4) for j in range(4)) / float(big)
        Wp.add(err, "%s (the quadric of %s after meshes.%s)" % (sh.label, parent_label, opname))
        counts["placed"] += 1


# ------------------------------------------------------------------------------- (5) poles
def check_poles(design, surfs, mesh_js, Wpole, counts):
    """a mobius with "poles": the output surfaces built from it (by name chain) collapse their
    first / last patch row's outer side to the requested points, moved by later translates"""
    meshes = design["meshes"]
    outs = design.get("output")
    outs = [outs] if isinstance(outs, str) else (outs or [list(meshes)[-1]])
    for si, name in enumerate(outs):
        shift = [0.0, 0.0, 0.0]
        cur = name
        poles = None
        while cur in meshes:
            op = meshes[cur]
            if "mobius" in op and "poles" in op:
                poles = op["poles"]
                break
            if "transform" in op:
                if any(k in op for k in ("rotate", "scale", "matrix")):
                    break
                t = op.get("translate", [0, 0, 0])
                shift = [shift[k] + t[k] for k in range(3)]
                cur = op["transform"]
            elif "cap" in op:
                cur = op["cap"]
            else:
                break
        if poles is None or si >= len(surfs):
            continue
        s = surfs[si]
        for which, j, v in (("south", 0, 0), ("north", s.nv - 1, 3)):
            if which not in poles:
                continue
            want = [poles[which][k] + shift[k] for k in range(3)]
            for i in range(s.nu):
                P = s.patch(i, j)
                for r in range(P.du + 1):
                    x = P.point3(r, 0 if v == 0 else P.dv)
                    err = math.sqrt(sum((x[k] - want[k]) ** 2 for k in range(3))) / s.size
                    Wpole.add(err, "surface %d %s pole, patch (%d,%d)" % (si, which, i, j))
            counts["poles"] += 1


# ------------------------------------------------------------------ designs of the audit's own
# The shapes and caps the examples do not reach: every named shape (cone, ellipsoid,
# hyperboloid1_ruled, hypar among them) under rotations about oblique axes, non-uniform scales
# and a shearing matrix; and polar meshes of an ellipsoid, a sphere (Moebius-placed poles), a
# paraboloid and a two-sheeted hyperboloid, capped (general-quadratic caps: degree (4, 3)).
OWN_DESIGNS = {
    "audit_all_shapes.json": r"""{
  "shapes": {
    "tor": {"kind": "torus", "R": 2.5, "r": 0.7, "rotate": {"axis": [1, 2, 3], "degrees": 33}, "translate": [1, -2, 0.5]},
    "cyc": {"kind": "cyclide", "a": 2, "c": 0.7, "mu": 1.2, "scale": 1.5},
    "sph": {"kind": "sphere", "radius": 1.7, "translate": [0.3, 0.2, 0.1]},
    "ell": {"kind": "ellipsoid", "a": 2, "b": 1.5, "c": 0.8, "rotate": {"axis": [0, 1, 1], "degrees": 40}},
    "cyl": {"kind": "cylinder", "radius": 0.8, "scale": [1, 2, 1]},
    "con": {"kind": "cone", "k": 1.3},
    "h1r": {"kind": "hyperboloid1_ruled", "a": 1.1, "c": 0.7},
    "h1": {"kind": "hyperboloid1", "a": 0.9, "c": 1.2},
    "h2": {"kind": "hyperboloid2", "a": 0.6, "c": 0.9},
    "par": {"kind": "paraboloid", "A": 1.2, "B": 0.7},
    "hyp": {"kind": "hypar", "A": 1.5, "B": 0.8, "matrix": [1, 0.1, 0, 0.2, 0, 1, 0.3, 0, 0, 0, 1, 0.1, 0, 0, 0, 1]}
  },
  "meshes": {
    "m_tor": {"shape": "tor", "u": {"arcs": [50, 40, 70, 60, 45, 55, 40]}, "v": {"arcs": 5}},
    "m_cyc": {"shape": "cyc"},
    "m_sph": {"shape": "sph", "u": {"arcs": 7}, "v": {"knots": [0.1, 0.3, 0.45, 0.7, 0.92]}},
    "m_ell": {"shape": "ell"},
    "m_cyl": {"shape": "cyl", "u": {"arcs": 5, "from": 10, "to": 300}},
    "m_con": {"shape": "con"},
    "m_h1r": {"shape": "h1r"},
    "m_h1": {"shape": "h1"},
    "m_h2": {"shape": "h2", "v": {"knots": [0.1, 0.3, 0.5, 0.7]}},
    "m_par": {"shape": "par"},
    "m_hyp": {"shape": "hyp", "u": {"knots": [-1, -0.2, 0.5, 1.3]}}
  },
  "output": ["m_tor", "m_cyc", "m_sph", "m_ell", "m_cyl", "m_con", "m_h1r", "m_h1", "m_h2", "m_par", "m_hyp"]
}""",
    "audit_caps.json": r"""{
  "shapes": {
    "ell": {"kind": "ellipsoid", "a": 2, "b": 1.5, "c": 0.8, "rotate": {"axis": [1, 1, 0], "degrees": 25}},
    "sph": {"kind": "sphere", "radius": 1.2, "translate": [5, 0, 0]},
    "par": {"kind": "paraboloid", "A": 1.2, "B": 0.7, "translate": [0, 5, 0]},
    "h2": {"kind": "hyperboloid2", "a": 0.6, "c": 0.9, "translate": [5, 5, 0]}
  },
  "meshes": {
    "pe": {"polar": "ell", "u": {"arcs": 7}, "v": {"knots": [0.2, 0.4, 0.55, 0.8]}},
    "ce": {"cap": "pe", "quadratic": "general"},
    "ps": {"polar": "sph", "u": {"arcs": 10}, "v": {"knots": [0.12, 0.25, 0.38, 0.5, 0.62, 0.75, 0.88]}},
    "ms": {"mobius": "ps", "sphere": "sph", "poles": {"south": [5.0, 0.72, -0.96], "north": [5.0, 0.0, 1.2]}},
    "cs": {"cap": "ms", "quadratic": "general"},
    "pp": {"polar": "par", "u": {"arcs": 8}, "v": {"knots": [0.3, 0.6, 1.0]}},
    "cp": {"cap": "pp"},
    "ph": {"polar": "h2", "u": {"arcs": 6}, "v": {"knots": [0.2, 0.4, 0.6]}},
    "ch": {"cap": "ph", "quadratic": "general"}
  },
  "output": ["ce", "cs", "cp", "ch"]
}""",
}


# --------------------------------------------------------------------------------- driver
def run_rg2(rg2, args):
    r = subprocess.run([rg2] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s %s: exit %d: %s" % (rg2, " ".join(args), r.returncode, r.stderr.strip()))


def audit(design_path, dump, meshf, bvf=None, bezf=None, stepf=None, igsf=None):
    with open(design_path) as f:
        design = json.load(f)
    with open(dump) as f:
        dj = json.load(f)
    with open(meshf) as f:
        mj = json.load(f)
    surfs = [Surface(x) for x in dj["surfaces"]]
    shapes = [PlacedShape(x) for x in mj["shapes"]]
    counts = {"pole": 0, "unmeasured": 0, "measured": 0, "built": 0, "build_skipped": 0, "placed": 0,
              "poles": 0, "collapsed": 0, "exported": 0,
              "nurbs_intervals": 0, "nurbs_matched": 0, "cad": 0, "polar_points": 0}
    notes = []
    W = Worst("exact", LIMIT_EXACT)
    W0, W1, W2 = Worst("G0 gap", LIMIT_G0), Worst("G1 angle", LIMIT_G1), Worst("G2 jump", LIMIT_G2)
    W1p, W2p = Worst("G1 near pole", LIMIT_G1), Worst("G2 near pole", LIMIT_G2)
    Wlim = Worst("G1 at pole", LIMIT_G1)
    Wb, Wp, Wpole = Worst("construction", LIMIT_BUILD), Worst("placement", LIMIT_PLACE), Worst("pole", LIMIT_G0)
    per_shape = check_exact(surfs, shapes, W)
    check_seams(surfs, W0, W1, W2, W1p, W2p, Wlim, counts)
    check_construction(surfs, mj["meshes"], Wb, counts)
    check_placement(design, shapes, Wp, counts, notes)
    check_poles(design, surfs, mj["meshes"], Wpole, counts)
    Wc = Worst("collapsed", LIMIT_COLLAPSE)
    check_collapsed(surfs, Wc, counts)
    Wn = Worst("NURBS", LIMIT_BUILD)
    check_nurbs(design, surfs, Wn, counts)
    Wx = Worst("export", LIMIT_EXPORT)
    if bvf:
        check_exports(surfs, bvf, bezf, Wx, counts)
    Wz = Worst("eq. (13) poles", LIMIT_COLLAPSE)
    check_polar_points(design, mj["meshes"], shapes, Wz, counts)
    Wcad = [Worst("STEP/IGES ulp", 0.0), Worst("STEP/IGES pole", SNAP_ROUNDINGS),
            Worst("STEP/IGES one", 0), Worst("IGES = STEP", 0)]
    W1f, W2f = Worst("G1 pole file", LIMIT_G1), Worst("G2 pole file", LIMIT_G2)
    if stepf:
        step = check_cad(surfs, stepf, igsf, Wcad, counts)
        check_cad_poles(surfs, step, W1f, W2f, notes)
    allw = [W, W0, W1, W2, W1p, W2p, Wlim, Wb, Wn, Wp, Wpole, Wz, Wc, Wx] + Wcad + [W1f, W2f]
    return allw, per_shape, counts, notes, surfs


def report(name, res, verbose):
    """print one design's figures; True when all are within their limits"""
    allw, per_shape, counts, notes, surfs = res
    bad = [w for w in allw if not w.ok()] + [w for w in per_shape.values() if not w.ok()]
    print("%s: %d surfaces, %d patches; %d seam samples (%d at a pole: its limit normals, and beside it); "
          "%d patches rebuilt exactly; %d placements; %d collapsed sides; %d patches in .bv/.bez, %d in STEP/IGES%s" % (
              name, len(surfs), sum(len(s.patches) for s in surfs), counts["measured"], counts["pole"],
              counts["built"], counts["placed"], counts["collapsed"], counts["exported"], counts["cad"], "  FAIL" if bad else ""))
    for w in list(per_shape.values()) + allw[1:]:
        if verbose or not w.ok():
            print("    " + w.line())
    if counts["unmeasured"]:
        print("    note: %d samples beside a pole not measured (degenerate there too)" % counts["unmeasured"])
    for n in notes:
        print("    note: " + n)
    if counts["nurbs_intervals"]:
        print("    NURBS: %d of %d Bezier pieces (by blossoming) found among the patches" % (
            counts["nurbs_matched"], counts["nurbs_intervals"]))
    if counts["build_skipped"]:
        print("    note: %d surfaces not rebuilt (patch count differs)" % counts["build_skipped"])
    return not bad


def self_test(rg2, exdir, tmp):
    """the audit must be able to fail: one control point of an exact patch moved by 1e-9 of the
    size in the written file, inside the patch and on its border; each must be seen as off the
    shape, as a broken seam and as a patch the construction does not give"""
    global RES_N, SEAM_N
    name = "torus_sphere.json"
    path = os.path.join(exdir, name)
    dump = os.path.join(tmp, "selftest.patches.json")
    meshf = os.path.join(tmp, "selftest.mesh.json")
    run_rg2(rg2, ["build", path, "-o", dump, "-q"])
    run_rg2(rg2, ["mesh", path, "-o", meshf])
    with open(dump) as f:
        dj = json.load(f)
    s0 = dj["surfaces"][0]
    p = s0["tag"].index(0)                 # the first patch on the ring
    size = Surface(s0).size
    ok = True
    for (r, q) in ((1, 2), (3, 1)):
        js = json.loads(json.dumps(dj))
        k = 4 * (r * 4 + q)
        js["surfaces"][0]["patches"][p][k] += 1e-9 * size * js["surfaces"][0]["patches"][p][k + 3]
        bad = os.path.join(tmp, "selftest.perturbed.json")
        with open(bad, "w") as f:
            json.dump(js, f)
        saved, (RES_N, SEAM_N) = (RES_N, SEAM_N), (3, 3)    # enough to see 1e-9
        allw = audit(path, bad, meshf)[0]
        RES_N, SEAM_N = saved
        v = {w.name: w.val for w in allw}
        caught = (v["exact"] > LIMIT_EXACT and v["construction"] > LIMIT_BUILD
                  and (v["G0 gap"] > LIMIT_G0 or v["G1 angle"] > LIMIT_G1 or v["G2 jump"] > LIMIT_G2))
        print("self-test: %s patch (%d,%d), control point [%d][%d] moved by 1e-9 of the size: exact %.2e, "
              "G0 %.2e, G1 %.2e rad, G2 %.2e, construction %.2e: %s" % (
                  name, p // s0["nv"], p % s0["nv"], r, q, v["exact"], v["G0 gap"], v["G1 angle"], v["G2 jump"],
                  v["construction"], "caught" if caught else "MISSED"))
        ok = ok and caught
    return ok


def main(argv):
    verbose = "-v" in argv
    argv = [a for a in argv if a != "-v"]
    do_self_test = "--no-self-test" not in argv
    argv = [a for a in argv if a != "--no-self-test"]
    if len(argv) == 4 and argv[0] == "--files":
        # one design's files as they are (a patch dump edited by hand, say)
        ok = report(os.path.basename(argv[2]), audit(argv[1], argv[2], argv[3]), True)
        print("ok" if ok else "FAIL")
        return 0 if ok else 1
    only = None
    if "--examples" in argv:
        k = argv.index("--examples")
        only = argv[k + 1].split(",")
        del argv[k:k + 2]
    if len(argv) != 2:
        print(__doc__[__doc__.index("Usage:"):], file=sys.stderr)
        return 2
    rg2, src = argv
    exdir = os.path.join(src, "examples")
    names = sorted(f for f in os.listdir(exdir) if f.endswith(".json"))
    if only:
        names = [n for n in names if n in only or n[:-5] in only]
    t0 = time.time()
    failed = []
    mc = {"math_junctions": 0, "math_arcs": 0, "math_poles": 0}
    mf = check_math(mc)
    print("MATH.md in exact rationals: G2 (Definition 1) at %d junctions of random closed and open polygons, "
          "%d arcs of an open partition reproduced control point for control point, eq. (13) for %d pairs of "
          "polar knots: %s" % (mc["math_junctions"], mc["math_arcs"], mc["math_poles"], "; ".join(mf) if mf else "ok"))
    if mf:
        failed.append("MATH.md")
    with tempfile.TemporaryDirectory(prefix="rg2-audit-") as tmp:
        todo = [(name, os.path.join(exdir, name)) for name in names]
        if not only:
            for name, text in OWN_DESIGNS.items():
                with open(os.path.join(tmp, name), "w") as f:
                    f.write(text)
                todo.append((name, os.path.join(tmp, name)))
        for name, path in todo:
            dump = os.path.join(tmp, name[:-5] + ".patches.json")
            meshf = os.path.join(tmp, name[:-5] + ".mesh.json")
            bvf = os.path.join(tmp, name[:-5] + ".bv")
            bezf = os.path.join(tmp, name[:-5] + ".bez")
            stepf = os.path.join(tmp, name[:-5] + ".step")
            igsf = os.path.join(tmp, name[:-5] + ".igs")
            run_rg2(rg2, ["build", path, "-o", dump, "-o", bvf, "-o", bezf, "-o", stepf, "-o", igsf, "-q"])
            run_rg2(rg2, ["mesh", path, "-o", meshf])
            t1 = time.process_time()
            res = audit(path, dump, meshf, bvf, bezf, stepf, igsf)
            if verbose:
                print("(%s: %.1f s of CPU)" % (name, time.process_time() - t1))
            if not report(name, res, verbose):
                failed.append(name)
        if do_self_test and not self_test(rg2, exdir, tmp):
            failed.append("self-test")
    print("%s: %d designs in %.1f s" % ("FAIL (%s)" % ", ".join(failed) if failed else "ok", len(todo),
                                        time.time() - t0))
    return 1 if failed else 0


if __name__ == "__main__":
    if sys.version_info < (3, 9):       # math.ulp, math.comb, math.dist
        print("exact_audit: error: needs Python 3.9 or later (this is %d.%d)" % sys.version_info[:2], file=sys.stderr)
        sys.exit(1)
    try:
        sys.exit(main(sys.argv[1:]))
    except (RuntimeError, OSError, ValueError, KeyError) as e:
        print("exact_audit: error: %s" % e, file=sys.stderr)
        sys.exit(1)
