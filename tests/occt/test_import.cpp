// test_import.cpp -- OpenCASCADE as the real client of rg2's STEP and IGES: every exported
// file is read back with OCCT's STEP / IGES readers and checked for the face count, one
// connected shell with shared edges (IGES: after sewing), maximum tolerance, BRepCheck
// validity, OCCT's surface points against rg2's evaluation, the pcurves (STEP: exactly the
// sides of each face's parameter rectangle), and G2 (normals and normal curvatures evaluated
// by OCCT on both faces) across every shared edge.
extern "C" {
#include "../export_fixtures.h"
}

#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_Curve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeAnalysis_ShapeTolerance.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <dirent.h>
#include <algorithm>
#include <unistd.h>
#include <vector>

namespace {

struct Worst {
    double point = 0, angle = 0, curv = 0, tol = 0, exact = 0, pcurve = 0;
    int edges = 0, samples = 0;
};
Worst g_worst;

struct Case {
    const char *name;
    const rg2_surface *s;
    double scale;
    // distance of a point from the exact shape the surface represents (nullptr: none)
    double (*exact)(const double p[3]) = nullptr;
    bool ap242 = true; // also write AP242 (it differs from AP214 in the header only)
};

double torus_13_4(const double p[3]) { return fx_torus_dist(13.0, 4.0, p); }

// Expected counts for one surface: faces, edges shared by two face sides, free edges.
struct Expect {
    int faces, shared, free_edges;
};

// Patches of the first row whose v = 0 side (end 0), or of the last row whose v = 1 side
// (end 1), collapses to a point (a pole); with dir 1 the same for the u = 0 sides of the first
// column and the u = 1 sides of the last.
int collapsed_sides(const rg2_surface *s, int end, int dir = 0)
{
    if (dir ? s->closed_u : s->closed_v)
        return 0;
    double tol = 1e-11 * rg2t_surface_scale(s);
    int n = 0, along = dir ? s->nv : s->nu;
    for (int i = 0; i < along; i++) {
        rg2_xpatch P;
        if (dir)
            rg2_surface_patch_get(s, end ? s->nu - 1 : 0, i, &P);
        else
            rg2_surface_patch_get(s, i, end ? s->nv - 1 : 0, &P);
        int c0 = end ? (dir ? P.du : P.dv) : 0, na = dir ? P.dv : P.du;
        bool c = true;
        for (int a = 1; a <= na; a++)
            for (int d = 0; d < 3; d++) {
                const double *q = dir ? P.h[c0][a] : P.h[a][c0], *q0 = dir ? P.h[c0][0] : P.h[0][c0];
                if (std::fabs(q[d] / q[3] - q0[d] / q0[3]) > tol)
                    c = false;
            }
        n += c;
    }
    return n;
}

Expect expect_of(const rg2_surface *s, bool per_mesh)
{
    int cb0 = collapsed_sides(s, 0), cb1 = collapsed_sides(s, 1);
    int cu0 = collapsed_sides(s, 0, 1), cu1 = collapsed_sides(s, 1, 1);
    Expect e;
    if (per_mesh) {
        e.faces = 1;
        e.shared = (s->closed_u ? 1 : 0) + (s->closed_v ? 1 : 0);
        e.free_edges = (s->closed_u ? 0 : 2) + (s->closed_v ? 0 : 2) - (cb0 == s->nu ? 1 : 0) -
                       (cb1 == s->nu ? 1 : 0) - (cu0 == s->nv ? 1 : 0) - (cu1 == s->nv ? 1 : 0);
    } else {
        e.faces = s->nu * s->nv;
        e.shared = (s->nu - 1 + s->closed_u) * s->nv + (s->nv - 1 + s->closed_v) * s->nu;
        e.free_edges = (s->closed_u ? 0 : 2 * s->nv) + (s->closed_v ? 0 : 2 * s->nu) - cb0 - cb1 - cu0 - cu1;
    }
    return e;
}

double dot(const gp_Vec &a, const gp_Vec &b) { return a.Dot(b); }

// Normal curvature of the surface at props in the 3D tangent direction d (projected on the
// tangent plane), against the unit normal n.
double normal_curvature(GeomLProp_SLProps &pr, const gp_Vec &n, gp_Vec d)
{
    gp_Vec su = pr.D1U(), sv = pr.D1V();
    d -= n * d.Dot(n);
    double E = dot(su, su), F = dot(su, sv), G = dot(sv, sv);
    double r1 = dot(d, su), r2 = dot(d, sv), det = E * G - F * F;
    double a = (G * r1 - F * r2) / det, c = (E * r2 - F * r1) / det;
    gp_Vec t = su * a + sv * c;
    gp_Vec d2 = pr.D2U() * (a * a) + pr.DUV() * (2 * a * c) + pr.D2V() * (c * c);
    return d2.Dot(n) / t.Dot(t);
}

struct Occurrence {
    TopoDS_Face face;
    TopoDS_Edge edge; // oriented as in the face
};

// Evaluate OCCT props at the point of the edge occurrence with edge-curve parameter t.
// rg2's STEP files carry exact pcurves (check_pcurves), but for IGES OCCT computes them by
// projection, and near a pole they can be off by ~1e-9 in v, which would compare the two faces
// at slightly different points. So the pcurve's (u, v) is refined by Gauss-Newton until the
// face's point is the edge's 3D point p.
bool props_at(const Occurrence &o, double t, const gp_Pnt &p, Handle(Geom_Surface) & surf, gp_Pnt2d &uv)
{
    double f, l;
    Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(o.edge, o.face, f, l);
    if (pc.IsNull())
        return false;
    uv = pc->Value(t);
    surf = BRep_Tool::Surface(o.face);
    if (surf.IsNull())
        return false;
    double u = uv.X(), v = uv.Y(), u1, u2, v1, v2;
    surf->Bounds(u1, u2, v1, v2);
    for (int it = 0; it < 4; it++) {
        gp_Pnt q;
        gp_Vec du, dv;
        surf->D1(u, v, q, du, dv);
        gp_Vec r(q, p);
        double a = du.Dot(du), b = du.Dot(dv), c = dv.Dot(dv), det = a * c - b * b;
        if (!(det > 1e-300))
            break; // at a collapsed edge: keep the pcurve's value
        double x = du.Dot(r), y = dv.Dot(r);
        u = std::min(u2, std::max(u1, u + (c * x - b * y) / det));
        v = std::min(v2, std::max(v1, v + (a * y - b * x) / det));
    }
    uv.SetCoord(u, v);
    return true;
}

// G2 across every edge with two face occurrences; returns false if something is undefined.
void check_g2(const TopoDS_Shape &shape, double scale, const char *what, int *n_shared, int *n_free,
              std::vector<TopoDS_Face> &faces, std::vector<std::vector<int>> &adj)
{
    TopTools_IndexedMapOfShape edges, fmap;
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    TopExp::MapShapes(shape, TopAbs_FACE, fmap);
    std::vector<std::vector<Occurrence>> occ(edges.Extent() + 1);
    std::vector<std::vector<int>> occ_face(edges.Extent() + 1);
    faces.clear();
    for (int k = 1; k <= fmap.Extent(); k++)
        faces.push_back(TopoDS::Face(fmap(k)));
    adj.assign(faces.size(), std::vector<int>());
    for (size_t k = 0; k < faces.size(); k++)
        for (TopExp_Explorer ex(faces[k], TopAbs_EDGE); ex.More(); ex.Next()) {
            TopoDS_Edge e = TopoDS::Edge(ex.Current());
            if (BRep_Tool::Degenerated(e))
                continue;
            int id = edges.FindIndex(e);
            occ[id].push_back({faces[k], e});
            occ_face[id].push_back((int)k);
        }
    *n_shared = *n_free = 0;
    double worst_a = 0, worst_c = 0;
    int samples = 0;
    for (int id = 1; id <= edges.Extent(); id++) {
        if (occ[id].size() == 1)
            (*n_free)++;
        if (occ[id].size() != 2)
            continue;
        (*n_shared)++;
        adj[occ_face[id][0]].push_back(occ_face[id][1]);
        adj[occ_face[id][1]].push_back(occ_face[id][0]);
        double f, l;
        Handle(Geom_Curve) c3 = BRep_Tool::Curve(TopoDS::Edge(edges(id)), f, l);
        if (c3.IsNull())
            continue;
        for (int q = 1; q <= 7; q++) {
            double t = f + (l - f) * q / 8.0;
            gp_Pnt p;
            gp_Vec tang;
            c3->D1(t, p, tang);
            gp_Vec n[2];
            GeomLProp_SLProps *pr[2] = {nullptr, nullptr};
            Handle(Geom_Surface) surf[2];
            gp_Pnt2d uv[2];
            bool ok = true;
            for (int s = 0; s < 2 && ok; s++) {
                ok = props_at(occ[id][s], t, p, surf[s], uv[s]);
                if (!ok)
                    break;
                pr[s] = new GeomLProp_SLProps(surf[s], uv[s].X(), uv[s].Y(), 2, 1e-12);
                ok = pr[s]->IsNormalDefined();
                if (ok) {
                    n[s] = gp_Vec(pr[s]->Normal());
                    if (occ[id][s].face.Orientation() == TopAbs_REVERSED)
                        n[s].Reverse();
                }
            }
            if (ok) {
                double ang = n[0].Angle(n[1]);
                worst_a = std::max(worst_a, ang);
                gp_Vec tt = tang.Normalized(), cr = gp_Vec(n[0]).Crossed(tt);
                gp_Vec dirs[4] = {tt, cr, tt + cr, tt - cr};
                double kref = 1.0 / scale;
                if (pr[0]->IsCurvatureDefined())
                    kref = std::max(kref, std::max(std::fabs(pr[0]->MaxCurvature()), std::fabs(pr[0]->MinCurvature())));
                for (const gp_Vec &d : dirs) {
                    double k0 = normal_curvature(*pr[0], n[0], d), k1 = normal_curvature(*pr[1], n[1], d);
                    worst_c = std::max(worst_c, std::fabs(k0 - k1) / kref);
                }
                samples++;
            }
            delete pr[0];
            delete pr[1];
        }
    }
    CHECK(worst_a <= 1e-8, "%s: OCCT normal angle across shared edges %.3g rad", what, worst_a);
    CHECK(worst_c <= 1e-8, "%s: OCCT normal curvature jump across shared edges %.3g rel", what, worst_c);
    printf("  %-34s G2 through OCCT: %d shared edges, %d samples, normal angle %.2e rad, curvature %.2e rel\n",
           what, *n_shared, samples, worst_a, worst_c);
    g_worst.angle = std::max(g_worst.angle, worst_a);
    g_worst.curv = std::max(g_worst.curv, worst_c);
    g_worst.edges += *n_shared;
    g_worst.samples += samples;
}

// Every edge's pcurve on every face it bounds, as OCCT holds it. The faces are untrimmed, so each
// pcurve must be a side of the face's parameter rectangle [u1, u2] x [v1, v2] run at the edge's
// own parameter: one coordinate a bound, the other the affine map of t from one bound to the
// other. rg2's STEP files carry these lines, so there the deviation must be at rounding level,
// poles included. (When a file has no pcurves, as IGES, OCCT projects the edges; near a pole the
// parameter then comes out off by up to ~1e-9 while the point is right, so the point distance
// S(pcurve(t)) - C(t), also measured, cannot show it.)
void check_pcurves(const TopoDS_Shape &shape, double scale, const char *what, bool exact)
{
    double worst_uv = 0, worst_pt = 0;
    int occurrences = 0, lines = 0;
    for (TopExp_Explorer fx(shape, TopAbs_FACE); fx.More(); fx.Next()) {
        TopoDS_Face face = TopoDS::Face(fx.Current());
        Handle(Geom_Surface) surf = BRep_Tool::Surface(face);
        if (surf.IsNull())
            continue;
        double b[4];
        surf->Bounds(b[0], b[1], b[2], b[3]);
        for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
            TopoDS_Edge e = TopoDS::Edge(ex.Current());
            if (BRep_Tool::Degenerated(e))
                continue;
            double f, l, f3, l3;
            Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, f, l);
            Handle(Geom_Curve) c3 = BRep_Tool::Curve(e, f3, l3);
            CHECK(!pc.IsNull() && !c3.IsNull(), "%s: an edge without pcurve or 3D curve", what);
            if (pc.IsNull() || c3.IsNull())
                continue;
            occurrences++;
            Handle(Geom2d_Curve) basis = pc;
            while (basis->IsKind(STANDARD_TYPE(Geom2d_TrimmedCurve)))
                basis = Handle(Geom2d_TrimmedCurve)::DownCast(basis)->BasisCurve();
            lines += basis->IsKind(STANDARD_TYPE(Geom2d_Line));
            gp_Pnt2d a = pc->Value(f), z = pc->Value(l);
            int fixed = std::fabs(a.X() - z.X()) <= std::fabs(a.Y() - z.Y()) ? 0 : 1; // 0: u constant
            int freec = 1 - fixed;
            double lo = b[2 * freec], hi = b[2 * freec + 1];
            bool up = (freec ? a.Y() : a.X()) < 0.5 * (lo + hi);
            double size = std::max(b[1] - b[0], b[3] - b[2]);
            for (int q = 0; q <= 8; q++) {
                double t = f + (l - f) * q / 8.0, s = (t - f) / (l - f);
                gp_Pnt2d uv = pc->Value(t);
                double fc = fixed ? uv.Y() : uv.X(), fr = freec ? uv.Y() : uv.X();
                double dfix = std::min(std::fabs(fc - b[2 * fixed]), std::fabs(fc - b[2 * fixed + 1]));
                double dfree = std::fabs(fr - (up ? lo + s * (hi - lo) : hi - s * (hi - lo)));
                worst_uv = std::max(worst_uv, std::max(dfix, dfree) / size);
                worst_pt = std::max(worst_pt, surf->Value(uv.X(), uv.Y()).Distance(c3->Value(t)) / scale);
            }
        }
    }
    if (exact) {
        CHECK(worst_uv <= 1e-14, "%s: pcurves off the sides of the parameter rectangle by %.3g", what, worst_uv);
        CHECK(worst_pt <= 1e-13, "%s: pcurve points off their edges by %.3g relative", what, worst_pt);
        CHECK(lines == occurrences, "%s: %d of %d pcurves are lines", what, lines, occurrences);
        g_worst.pcurve = std::max(g_worst.pcurve, worst_uv);
    }
    printf("  %-34s pcurves: %d edge uses, %d lines, parameter %.2e, point %.2e relative%s\n", what, occurrences,
           lines, worst_uv, worst_pt, exact ? "" : " (computed by OCCT)");
}

// OCCT's surface points against rg2's evaluation (rg2_surface_eval: patches of any degree):
// each face is matched to the patch (per patch layout) by its centre and must carry that
// patch's degrees; per mesh, patch (i, j) is the knot span [i, i+1] x [j, j+1] of one surface
// of the surface's highest degrees. With c.exact, OCCT's points must lie on the exact shape.
void check_points(const std::vector<TopoDS_Face> &faces, const Case &c, bool per_mesh, const char *what)
{
    const rg2_surface *s = c.s;
    double scale = c.scale;
    double worst = 0, worst_exact = 0;
    int matched = 0, bad_degree = 0;
    std::vector<int> used(s->nu * s->nv, 0);
    auto exact_at = [&](const gp_Pnt &p) {
        if (c.exact) {
            double x[3] = {p.X(), p.Y(), p.Z()};
            worst_exact = std::max(worst_exact, c.exact(x) / scale);
        }
    };
    for (const TopoDS_Face &F : faces) {
        Handle(Geom_Surface) S = BRep_Tool::Surface(F);
        Handle(Geom_BSplineSurface) B = Handle(Geom_BSplineSurface)::DownCast(S);
        if (per_mesh) {
            int du, dv;
            rg2_surface_degree(s, &du, &dv);
            bad_degree += B.IsNull() || B->UDegree() != du || B->VDegree() != dv;
            for (int i = 0; i < s->nu; i++)
                for (int j = 0; j < s->nv; j++)
                    for (int a = 0; a <= 4; a++)
                        for (int b = 0; b <= 4; b++) {
                            rg2_eval e;
                            rg2_surface_eval(s, i, j, a / 4.0, b / 4.0, 0, &e);
                            gp_Pnt p = S->Value(i + a / 4.0, j + b / 4.0);
                            worst = std::max(worst, p.Distance(gp_Pnt(e.p[0], e.p[1], e.p[2])) / scale);
                            exact_at(p);
                        }
            matched++;
            continue;
        }
        gp_Pnt ctr = S->Value(0.5, 0.5);
        int best = -1;
        double bd = 1e300;
        for (int k = 0; k < s->nu * s->nv; k++) {
            rg2_eval e;
            rg2_surface_eval(s, k / s->nv, k % s->nv, 0.5, 0.5, 0, &e);
            double d = ctr.Distance(gp_Pnt(e.p[0], e.p[1], e.p[2]));
            if (d < bd) {
                bd = d;
                best = k;
            }
        }
        if (best < 0 || used[best])
            continue;
        used[best] = 1;
        matched++;
        rg2_xpatch X;
        rg2_surface_patch_get(s, best / s->nv, best % s->nv, &X);
        bad_degree += B.IsNull() || B->UDegree() != X.du || B->VDegree() != X.dv;
        for (int a = 0; a <= 6; a++)
            for (int b = 0; b <= 6; b++) {
                rg2_eval e;
                rg2_xpatch_eval(&X, a / 6.0, b / 6.0, 0, &e);
                gp_Pnt p = S->Value(a / 6.0, b / 6.0);
                worst = std::max(worst, p.Distance(gp_Pnt(e.p[0], e.p[1], e.p[2])) / scale);
                exact_at(p);
            }
    }
    CHECK(matched == (int)faces.size(), "%s: %d of %zu faces matched to patches", what, matched, faces.size());
    CHECK(bad_degree == 0, "%s: %d faces whose B-spline degrees are not their patches'", what, bad_degree);
    CHECK(worst <= 1e-12, "%s: OCCT point vs rg2 %.3g relative", what, worst);
    CHECK(worst_exact <= 1e-12, "%s: OCCT points %.3g (relative) off the exact shape", what, worst_exact);
    if (c.exact)
        printf("  %-34s points: %zu faces, OCCT vs rg2 %.2e, vs exact shape %.2e relative\n", what,
               faces.size(), worst, worst_exact);
    else
        printf("  %-34s points: %zu faces, OCCT vs rg2 %.2e relative\n", what, faces.size(), worst);
    g_worst.point = std::max(g_worst.point, worst);
    g_worst.exact = std::max(g_worst.exact, worst_exact);
}

// Normal and normal curvature in direction d from derivatives (local evaluation).
struct Jet {
    gp_Vec su, sv, suu, suv, svv, n;
};

double jet_curvature(const Jet &j, gp_Vec d)
{
    d -= j.n * d.Dot(j.n);
    double E = dot(j.su, j.su), F = dot(j.su, j.sv), G = dot(j.sv, j.sv);
    double r1 = dot(d, j.su), r2 = dot(d, j.sv), det = E * G - F * F;
    double a = (G * r1 - F * r2) / det, c = (E * r2 - F * r1) / det;
    gp_Vec t = j.su * a + j.sv * c;
    gp_Vec d2 = j.suu * (a * a) + j.suv * (2 * a * c) + j.svv * (c * c);
    return d2.Dot(j.n) / t.Dot(t);
}

// Index (1-based) of the knot equal to x, or 0.
int knot_index(const TColStd_Array1OfReal &k, double x)
{
    for (int q = k.Lower(); q <= k.Upper(); q++)
        if (std::fabs(k(q) - x) < 1e-12)
            return q;
    return 0;
}

// Per-mesh layout: the patch seams are interior knot lines of one B-spline face, not edges.
// G2 across them through OCCT: LocalD2 on the spans left and right of each knot line.
void check_knot_lines(const TopoDS_Face &F, const rg2_surface *s, double scale, const char *what)
{
    Handle(Geom_BSplineSurface) B = Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(F));
    CHECK(!B.IsNull(), "%s: the face is not a B-spline surface", what);
    if (B.IsNull())
        return;
    TColStd_Array1OfReal ku(1, B->NbUKnots()), kv(1, B->NbVKnots());
    B->UKnots(ku);
    B->VKnots(kv);
    double worst_a = 0, worst_c = 0;
    int samples = 0;
    for (int dir = 0; dir < 2; dir++) {
        int nlines = dir == 0 ? s->nu : s->nv, nother = dir == 0 ? s->nv : s->nu;
        for (int line = 1; line < nlines; line++)
            for (int span = 0; span < nother; span++)
                for (int q = 1; q <= 3; q++) {
                    double t = span + q / 4.0;
                    int kl = knot_index(dir == 0 ? ku : kv, line);
                    int ko = knot_index(dir == 0 ? kv : ku, span);
                    if (!kl || !ko)
                        continue;
                    Jet j[2];
                    for (int side = 0; side < 2; side++) {
                        int a1 = kl - 1 + side, a2 = kl + side;
                        gp_Pnt p;
                        if (dir == 0)
                            B->LocalD2(line, t, a1, a2, ko, ko + 1, p, j[side].su, j[side].sv, j[side].suu,
                                       j[side].svv, j[side].suv);
                        else
                            B->LocalD2(t, line, ko, ko + 1, a1, a2, p, j[side].su, j[side].sv, j[side].suu,
                                       j[side].svv, j[side].suv);
                        j[side].n = j[side].su.Crossed(j[side].sv).Normalized();
                    }
                    worst_a = std::max(worst_a, j[0].n.Angle(j[1].n));
                    gp_Vec tt = (dir == 0 ? j[0].sv : j[0].su).Normalized(), cr = j[0].n.Crossed(tt);
                    gp_Vec dirs[4] = {tt, cr, tt + cr, tt - cr};
                    double kref = 1.0 / scale;
                    for (const gp_Vec &d : dirs)
                        kref = std::max(kref, std::fabs(jet_curvature(j[0], d)));
                    for (const gp_Vec &d : dirs)
                        worst_c = std::max(worst_c, std::fabs(jet_curvature(j[0], d) - jet_curvature(j[1], d)) / kref);
                    samples++;
                }
    }
    CHECK(worst_a <= 1e-8, "%s: OCCT normal angle across knot lines %.3g rad", what, worst_a);
    CHECK(worst_c <= 1e-8, "%s: OCCT normal curvature jump across knot lines %.3g rel", what, worst_c);
    printf("  %-34s G2 across interior knot lines through OCCT: %d samples, normal angle %.2e rad, curvature %.2e rel\n",
           what, samples, worst_a, worst_c);
    g_worst.angle = std::max(g_worst.angle, worst_a);
    g_worst.curv = std::max(g_worst.curv, worst_c);
    g_worst.samples += samples;
}

int count_shells(const TopoDS_Shape &shape)
{
    TopTools_IndexedMapOfShape m;
    TopExp::MapShapes(shape, TopAbs_SHELL, m);
    return m.Extent();
}

bool connected(const std::vector<std::vector<int>> &adj)
{
    if (adj.empty())
        return false;
    std::vector<int> seen(adj.size(), 0), stack{0};
    seen[0] = 1;
    size_t n = 1;
    while (!stack.empty()) {
        int f = stack.back();
        stack.pop_back();
        for (int g : adj[f])
            if (!seen[g]) {
                seen[g] = 1;
                n++;
                stack.push_back(g);
            }
    }
    return n == adj.size();
}

// brep: IGES as B-rep shells (rg2_export_opts.iges_brep), read without sewing.
void check_file(const Case &c, const std::string &dir, const char *ext, int layout, int ap242, int brep = 0)
{
    bool per_mesh = layout == RG2_STEP_FACE_PER_MESH, iges = ext[0] == 'i';
    std::string path = dir + "/" + c.name + (per_mesh ? "_mesh" : "_patch") + (ap242 ? "_ap242" : "") +
                       (brep ? "_brep" : "") + "." + ext;
    char what[128];
    snprintf(what, sizeof what, "%s%s%s%s.%s", c.name, per_mesh ? " per-mesh" : " per-patch", ap242 ? " AP242" : "",
             brep ? " B-rep" : "", ext);
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.layout = (rg2_step_layout)layout;
    o.ap242 = ap242;
    o.iges_brep = brep;
    o.name = c.name;
    rg2_error err;
    rg2_status st = rg2_export_file(c.s, 1, path.c_str(), &o, &err);
    CHECK(st == RG2_OK, "%s: export failed: %s", what, err.msg);
    if (st)
        return;
    TopoDS_Shape shape;
    if (iges) {
        IGESControl_Reader r;
        bool ok = r.ReadFile(path.c_str()) == IFSelect_RetDone;
        CHECK(ok, "%s: IGES read failed", what);
        if (!ok)
            return;
        int nroots = r.NbRootsForTransfer();
        r.TransferRoots();
        TopoDS_Shape raw = r.OneShape();
        TopTools_IndexedMapOfShape fm;
        TopExp::MapShapes(raw, TopAbs_FACE, fm);
        // every entity is in the shell or is a face: no curve of its own among the roots (the
        // per-mesh B-rep's unused pcurves of pole sides came back as two stray edges)
        TopTools_IndexedDataMapOfShapeListOfShape ef;
        TopExp::MapShapesAndAncestors(raw, TopAbs_EDGE, TopAbs_FACE, ef);
        int stray = 0;
        for (int k = 1; k <= ef.Extent(); k++)
            stray += ef(k).IsEmpty();
        int want_roots = brep ? 1 : expect_of(c.s, per_mesh).faces;
        CHECK(stray == 0 && nroots == want_roots, "%s: %d roots (expected %d), %d edges outside every face", what,
              nroots, want_roots, stray);
        Expect e = expect_of(c.s, per_mesh);
        CHECK(fm.Extent() == e.faces, "%s: %d faces before sewing, expected %d", what, fm.Extent(), e.faces);
        if (brep) // the file's own topology: no sewing
            shape = raw;
        else {
            BRepBuilderAPI_Sewing sew(1e-6);
            sew.Add(raw);
            sew.Perform();
            shape = sew.SewedShape();
        }
    } else {
        STEPControl_Reader r;
        bool ok = r.ReadFile(path.c_str()) == IFSelect_RetDone;
        CHECK(ok, "%s: STEP read failed", what);
        if (!ok)
            return;
        int roots = r.TransferRoots();
        CHECK(roots >= 1, "%s: %d roots transferred", what, roots);
        shape = r.OneShape();
    }
    Expect e = expect_of(c.s, per_mesh);
    int shells = count_shells(shape);
    std::vector<TopoDS_Face> faces;
    std::vector<std::vector<int>> adj;
    int n_shared = 0, n_free = 0;
    check_g2(shape, c.scale, what, &n_shared, &n_free, faces, adj);
    CHECK((int)faces.size() == e.faces, "%s: %zu faces, expected %d", what, faces.size(), e.faces);
    // a single face may come back bare (IGES per mesh): then there is no shell to count
    CHECK(shells == 1 || (e.faces == 1 && shells == 0), "%s: %d shells, expected 1", what, shells);
    CHECK(n_shared == e.shared, "%s: %d shared edges, expected %d", what, n_shared, e.shared);
    CHECK(n_free == e.free_edges, "%s: %d free edges, expected %d", what, n_free, e.free_edges);
    CHECK(connected(adj), "%s: the faces are not one connected piece", what);
    double tol = ShapeAnalysis_ShapeTolerance().Tolerance(shape, 1);
    CHECK(tol <= 1e-6, "%s: maximum tolerance %.3g", what, tol);
    g_worst.tol = std::max(g_worst.tol, tol);
    BRepCheck_Analyzer an(shape);
    CHECK(an.IsValid(), "%s: BRepCheck says invalid", what);
    printf("  %-34s faces %zu, shells %d, shared %d, free %d, max tolerance %.2e, valid %d\n", what, faces.size(),
           shells, n_shared, n_free, tol, (int)an.IsValid());
    check_points(faces, c, per_mesh, what);
    check_pcurves(shape, c.scale, what, !iges || brep);
    if (per_mesh && faces.size() == 1)
        check_knot_lines(faces[0], c.s, c.scale, what);
    if (!getenv("RG2_OCCT_KEEP"))
        remove(path.c_str());
}

} // namespace

int main()
{
    // OCCT prints translation messages on its default messenger; keep the log readable.
    if (!getenv("RG2_OCCT_VERBOSE"))
        Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    char tmpl[] = "/tmp/rg2_occt_XXXXXX";
    const char *dir = mkdtemp(tmpl);
    if (!dir) {
        perror("mkdtemp");
        return 1;
    }
    rg2_surface torus, random, pole;
    memset(&torus, 0, sizeof torus);
    memset(&random, 0, sizeof random);
    memset(&pole, 0, sizeof pole);
    rg2_error err;
    CHECK_OK(fx_torus(13.0, 4.0, 8, 6, &torus, &err), &err);
    CHECK_OK(fx_random(20261122, 7, 6, &random, &err), &err);
    CHECK_OK(fx_pole(6, 7, &pole, &err), &err);
    rg2_surface pole_t; // the same, u and v exchanged: the pole on a u = 0 side
    memset(&pole_t, 0, sizeof pole_t);
    CHECK_OK(fx_pole_t(7, 6, &pole_t, &err), &err);
    CHECK(collapsed_sides(&pole, 0) == 6 && collapsed_sides(&pole_t, 0, 1) == 6 && collapsed_sides(&pole_t, 0) == 0,
          "pole sides: %d at v = 0, transposed %d at u = 0", collapsed_sides(&pole, 0), collapsed_sides(&pole_t, 0, 1));
    /* a complete sphere: polar mesh + bi-3 caps (both ends collapsed, docs/poles.md) */
    rg2_surface capped;
    memset(&capped, 0, sizeof capped);
    {
        double alpha[6] = {M_PI / 3, M_PI / 3, M_PI / 3, M_PI / 3, M_PI / 3, M_PI / 3}, v[4] = {0.2, 0.4, 0.6, 0.8};
        rg2_mesh m;
        memset(&m, 0, sizeof m);
        CHECK_OK(rg2_polar_sphere_mesh(alpha, 6, 0.0, v, 4, NULL, &m, &err), &err);
        CHECK_OK(rg2_cap_build(&m, NULL, &capped, NULL, &err), &err);
        rg2_mesh_free(&m);
    }
    // the same surfaces with some patches replaced by their exact degree elevations
    // (rg2t_elevate_some): faces of degree (4, 3), (5, 3), (4, 4), (3, 5) next to bi-3 ones
    // (edges between patches of different degree), and one face of the highest degree per mesh
    rg2_surface torus_x, pole_x, capped_x;
    static const int xdeg[4][2] = {{4, 3}, {5, 3}, {4, 4}, {3, 5}}, xstride[4] = {3, 5, 7, 4};
    CHECK_OK(rg2_surface_copy(&torus, &torus_x, &err), &err);
    CHECK_OK(rg2_surface_copy(&pole, &pole_x, &err), &err);
    CHECK_OK(rg2_surface_copy(&capped, &capped_x, &err), &err);
    for (int k = 0; k < 4; k++) {
        CHECK_OK(rg2t_elevate_some(&torus_x, xdeg[k][0], xdeg[k][1], xstride[k], k, &err), &err);
        int ph = (k + 1) % xstride[k]; // puts a (4, 3) patch at the pole
        CHECK_OK(rg2t_elevate_some(&pole_x, xdeg[k][0], xdeg[k][1], xstride[k], ph, &err), &err);
        CHECK_OK(rg2t_elevate_some(&capped_x, xdeg[k][0], xdeg[k][1], xstride[k], k, &err), &err);
    }
    // one genuinely degree-(5, 4) patch (not an elevation): random weights and a perturbed grid
    rg2_surface single;
    memset(&single, 0, sizeof single);
    {
        single.nu = single.nv = 1;
        single.patch = (rg2_patch *)calloc(1, sizeof(rg2_patch));
        single.xp = (rg2_xpatch *)calloc(1, sizeof(rg2_xpatch));
        single.bu = (double *)calloc(1, sizeof(double));
        single.gu = (double *)calloc(1, sizeof(double));
        single.bv = (double *)calloc(1, sizeof(double));
        single.gv = (double *)calloc(1, sizeof(double));
        rg2t_rng rng;
        rg2t_seed(&rng, 20261122);
        rg2_xpatch &X = single.xp[0];
        X.du = 5;
        X.dv = 4;
        for (int r = 0; r <= X.du; r++)
            for (int t = 0; t <= X.dv; t++) {
                double w = rg2t_uniform(&rng, 0.5, 2.0);
                double p[3] = {2.0 * r + rg2t_uniform(&rng, -0.4, 0.4), 2.0 * t + rg2t_uniform(&rng, -0.4, 0.4),
                               rg2t_uniform(&rng, -2.0, 2.0)};
                for (int d = 0; d < 3; d++)
                    X.h[r][t][d] = w * p[d];
                X.h[r][t][3] = w;
            }
        for (int k = 0; k < 64; k++)
            (&single.patch[0].h[0][0][0])[k] = NAN;
    }
    // the torus with every 4-tuple multiplied by 1e-10 (rg2_surface_transform: the same surface,
    // weights about 1e-10): OCCT's IGES reader took weights below its 1e-9 for non-positive ones
    // and made them all 1, every IGES form 1.5e-3 of the size off rg2's points (5.7e-4 off the
    // torus) without a message, until the IGES writer multiplied such entities' weights by a
    // power of two
    rg2_surface torus_w;
    CHECK_OK(rg2_surface_copy(&torus, &torus_w, &err), &err);
    {
        const double M[16] = {1e-10, 0, 0, 0, 0, 1e-10, 0, 0, 0, 0, 1e-10, 0, 0, 0, 0, 1e-10};
        rg2_surface_transform(&torus_w, M);
    }
    printf("seed 20261122\n");
    Case cases[] = {{"torus", &torus, rg2t_surface_scale(&torus), torus_13_4},
                    {"random", &random, rg2t_surface_scale(&random)},
                    {"pole", &pole, rg2t_surface_scale(&pole)},
                    {"pole transposed", &pole_t, rg2t_surface_scale(&pole_t)},
                    {"capped sphere", &capped, rg2t_surface_scale(&capped)},
                    {"torus elevated", &torus_x, rg2t_surface_scale(&torus_x), torus_13_4, false},
                    {"pole elevated", &pole_x, rg2t_surface_scale(&pole_x), nullptr, false},
                    {"capped sphere elevated", &capped_x, rg2t_surface_scale(&capped_x), nullptr, false},
                    {"random (5, 4) patch", &single, rg2t_surface_scale(&single), nullptr, false},
                    {"torus, weights times 1e-10", &torus_w, rg2t_surface_scale(&torus_w), torus_13_4, false}};
    // every named shape with its default partition (rg2_shape_surface); shapes whose patches
    // have a weight <= 0 must be refused for STEP, naming the patch
    std::vector<rg2_surface> shapes;
    std::vector<std::string> shape_names;
    for (int k = 0; k < RG2_SHAPE_COUNT; k++) {
        const rg2_shape_desc *d = rg2_shape_describe((rg2_shape_kind)k);
        if (!d)
            continue;
        rg2_shape sh;
        rg2_shape_init(&sh, (rg2_shape_kind)k);
        rg2_partition pp[2];
        double vals[2][64];
        bool ok = true;
        for (int q = 0; q < 2 && ok; q++)
            ok = rg2_partition_equal(&pp[q], d->dir_kind[q], d->default_closed[q], d->default_range[q][0],
                                     d->default_range[q][1], d->default_segments[q], vals[q], 64, &err) == RG2_OK;
        rg2_surface surf;
        memset(&surf, 0, sizeof surf);
        rg2_weight_report rep;
        ok = ok && rg2_shape_surface(&sh, &pp[0], &pp[1], &surf, &rep, &err) == RG2_OK;
        CHECK(ok, "shape %s: %s", d->name, err.msg);
        if (!ok)
            continue;
        if (rep.n_nonpositive) {
            std::string path = std::string(dir) + "/" + d->name + ".step";
            rg2_status st = rg2_export_file(&surf, 1, path.c_str(), nullptr, &err);
            CHECK(st == RG2_EWEIGHT && strstr(err.msg, "patch ("), "shape %s with weight %g: %s", d->name,
                  rep.min_weight, err.msg);
            printf("  %-34s refused: %s\n", d->name, err.msg);
            rg2_surface_free(&surf);
            continue;
        }
        shapes.push_back(surf);
        shape_names.push_back(d->name);
    }
    for (size_t k = 0; k < shapes.size(); k++) {
        Case c = {shape_names[k].c_str(), &shapes[k], rg2t_surface_scale(&shapes[k])};
        check_file(c, dir, "step", RG2_STEP_FACE_PER_PATCH, 0);
        check_file(c, dir, "step", RG2_STEP_FACE_PER_MESH, 0);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_PATCH, 0);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_PATCH, 0, 1);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_MESH, 0, 1);
    }
    // every example design (examples/*.json): each output surface through STEP (both layouts)
    // and IGES, with the same face, connectivity, tolerance, point and G2 checks
    std::vector<std::string> examples;
    const std::string exdir = std::string(getenv("RG2_SRC") ? getenv("RG2_SRC") : ".") + "/examples";
    if (DIR *ed = opendir(exdir.c_str())) {
        while (struct dirent *ent = readdir(ed)) {
            std::string n = ent->d_name;
            if (n.size() > 5 && n.compare(n.size() - 5, 5, ".json") == 0)
                examples.push_back(n);
        }
        closedir(ed);
    }
    std::sort(examples.begin(), examples.end());
    CHECK(!examples.empty(), "no example designs found under examples/");
    for (const std::string &n : examples) {
        rg2_design *d = nullptr;
        std::string path = exdir + "/" + n;
        rg2_status st = rg2_design_load(path.c_str(), &d, &err);
        CHECK(st == RG2_OK, "%s: %s", path.c_str(), err.msg);
        if (st)
            continue;
        for (int k = 0; k < rg2_design_num_surfaces(d); k++) {
            std::string name = n.substr(0, n.size() - 5) + "_" + std::to_string(k);
            const rg2_surface *s = rg2_design_surface(d, k);
            Case c = {name.c_str(), s, rg2t_surface_scale(s)};
            check_file(c, dir, "step", RG2_STEP_FACE_PER_PATCH, 0);
            check_file(c, dir, "step", RG2_STEP_FACE_PER_MESH, 0);
            check_file(c, dir, "igs", RG2_STEP_FACE_PER_PATCH, 0);
            check_file(c, dir, "igs", RG2_STEP_FACE_PER_PATCH, 0, 1);
            check_file(c, dir, "igs", RG2_STEP_FACE_PER_MESH, 0, 1);
        }
        rg2_design_free(d);
    }
    for (const Case &c : cases) {
        check_file(c, dir, "step", RG2_STEP_FACE_PER_PATCH, 0);
        if (c.ap242)
            check_file(c, dir, "step", RG2_STEP_FACE_PER_PATCH, 1);
        check_file(c, dir, "step", RG2_STEP_FACE_PER_MESH, 0);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_PATCH, 0);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_PATCH, 0, 1);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_MESH, 0);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_MESH, 0, 1);
    }
    // a surface big enough that the STEP and IGES writers format their entities on the threads,
    // in several batches of blocks (src/step.c, emit_all), with patches of other degrees among
    // them (their entity counts differ)
    {
        rg2_surface big;
        memset(&big, 0, sizeof big);
        CHECK_OK(fx_random(20261204, 50, 50, &big, &err), &err);
        for (int k = 0; k < 4; k++)
            CHECK_OK(rg2t_elevate_some(&big, xdeg[k][0], xdeg[k][1], 5 * xstride[k], k, &err), &err);
        Case c = {"random 47 x 47, elevated in places", &big, rg2t_surface_scale(&big), nullptr, false};
        check_file(c, dir, "step", RG2_STEP_FACE_PER_PATCH, 0);
        check_file(c, dir, "step", RG2_STEP_FACE_PER_MESH, 0); // its net's points on the threads
        // src/iges.c: the B-rep's edges and faces through emit_items, its vertex list and the
        // merged net through pw_reals (test_export reads the plain layout's numbers back)
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_PATCH, 0, 1);
        check_file(c, dir, "igs", RG2_STEP_FACE_PER_MESH, 0);
        rg2_surface_free(&big);
    }
    printf("worst through OpenCASCADE: point %.2e relative (exact shapes %.2e), normal angle %.2e rad, "
           "normal curvature %.2e rel (%d shared edges, %d samples), max tolerance %.2e, STEP and IGES B-rep pcurves off the parameter rectangle %.2e\n",
           g_worst.point, g_worst.exact, g_worst.angle, g_worst.curv, g_worst.edges, g_worst.samples, g_worst.tol,
           g_worst.pcurve);
    for (rg2_surface &x : shapes)
        rg2_surface_free(&x);
    rg2_surface_free(&torus);
    rg2_surface_free(&random);
    rg2_surface_free(&pole);
    rg2_surface_free(&pole_t);
    rg2_surface_free(&capped);
    rg2_surface_free(&torus_x);
    rg2_surface_free(&pole_x);
    rg2_surface_free(&capped_x);
    rg2_surface_free(&single);
    rg2_surface_free(&torus_w);
    if (!getenv("RG2_OCCT_KEEP"))
        rmdir(dir);
    else
        printf("files kept in %s\n", dir);
    return rg2t_done("occt_import");
}
