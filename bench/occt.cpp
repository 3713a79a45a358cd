// occt.cpp -- the OpenCASCADE side of rg2_bench: a Geom_BSplineSurface from the same
// poles, weights and knots, evaluated per point through Geom_BSplineSurface, GeomAdaptor_Surface
// (span cache) and GeomLProp_SLProps, written as one face to STEP and IGES (and rg2's files
// read back), and picked: the closest point by GeomAPI_ProjectPointOnSurf, the first hit of a ray
// by GeomAPI_IntCS and by IntCurveSurface_HInter with its polyhedron kept. Plain C interface for
// bench.c.
#include "bench.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Tool.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include <Extrema_ExtAlgo.hxx>
#include <GeomAPI_IntCS.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Line.hxx>
#include <IntCurveSurface_HInter.hxx>
#include <IntCurveSurface_IntersectionPoint.hxx>
#include <IntCurveSurface_ThePolyhedronOfHInter.hxx>
#include <Standard_Failure.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <cmath>
#include <functional>

struct occt_surf {
    Handle(Geom_BSplineSurface) bs;
    GeomAdaptor_Surface adaptor;
    double lo[3], hi[3]; // the poles' box (the surface lies in it: weights > 0)
};

extern "C" occt_surf *occt_make(const bspline *b)
{
    int n1 = b->in1, n2 = b->in2;
    TColgp_Array2OfPnt poles(1, n1, 1, n2);
    TColStd_Array2OfReal weights(1, n1, 1, n2);
    for (int i = 0; i < n1; i++)
        for (int j = 0; j < n2; j++) {
            const double *h = b->hcoef + ((size_t)j * n1 + i) * 4;
            poles.SetValue(i + 1, j + 1, gp_Pnt(h[0] / h[3], h[1] / h[3], h[2] / h[3]));
            weights.SetValue(i + 1, j + 1, h[3]);
        }
    int s1 = b->spans1, s2 = b->spans2;
    TColStd_Array1OfReal uk(1, s1 + 1), vk(1, s2 + 1);
    TColStd_Array1OfInteger um(1, s1 + 1), vm(1, s2 + 1);
    for (int i = 0; i <= s1; i++) {
        uk.SetValue(i + 1, i);
        um.SetValue(i + 1, (i == 0 || i == s1) ? 4 : 3);
    }
    for (int j = 0; j <= s2; j++) {
        vk.SetValue(j + 1, j);
        vm.SetValue(j + 1, (j == 0 || j == s2) ? 4 : 3);
    }
    occt_surf *s = new occt_surf;
    s->bs = new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, 3, 3);
    s->adaptor.Load(s->bs);
    s->lo[0] = s->lo[1] = s->lo[2] = INFINITY;
    s->hi[0] = s->hi[1] = s->hi[2] = -INFINITY;
    for (int i = 1; i <= n1; i++)
        for (int j = 1; j <= n2; j++) {
            const gp_Pnt &q = poles.Value(i, j);
            double c[3] = {q.X(), q.Y(), q.Z()};
            for (int k = 0; k < 3; k++)
                s->lo[k] = std::fmin(s->lo[k], c[k]), s->hi[k] = std::fmax(s->hi[k], c[k]);
        }
    return s;
}

extern "C" void occt_free(occt_surf *s) { delete s; }

static void unit(const gp_Vec &du, const gp_Vec &dv, double *n)
{
    gp_Vec c = du.Crossed(dv);
    double l = c.Magnitude();
    double il = l > 0 ? 1.0 / l : 0.0;
    n[0] = c.X() * il;
    n[1] = c.Y() * il;
    n[2] = c.Z() * il;
}

static void put(const gp_Pnt &p, double *o)
{
    o[0] = p.X();
    o[1] = p.Y();
    o[2] = p.Z();
}

// Every point of the patch layout: patch (i, j), point (a, b) at u = i + a/(n-1), v = j + b/(n-1).
extern "C" void occt_eval(occt_surf *s, occt_method meth, const grid_params *g, double *pos, double *nrm,
                          double *K, double *H)
{
    GeomLProp_SLProps *props = meth == OCCT_SLPROPS ? new GeomLProp_SLProps(s->bs, 2, 1e-12) : nullptr;
    size_t idx = 0;
    for (int i = 0; i < g->pu; i++)
        for (int j = 0; j < g->pv; j++)
            for (int a = 0; a < g->n; a++) {
                double u = i + g->t[a];
                for (int b = 0; b < g->n; b++, idx++) {
                    double v = j + g->t[b];
                    gp_Pnt P;
                    gp_Vec du, dv;
                    switch (meth) {
                    case OCCT_BSPLINE_D0:
                        s->bs->D0(u, v, P);
                        put(P, pos + 3 * idx);
                        break;
                    case OCCT_BSPLINE_D1:
                        s->bs->D1(u, v, P, du, dv);
                        put(P, pos + 3 * idx);
                        unit(du, dv, nrm + 3 * idx);
                        break;
                    case OCCT_ADAPTOR_D0:
                        s->adaptor.D0(u, v, P);
                        put(P, pos + 3 * idx);
                        break;
                    case OCCT_ADAPTOR_D1:
                        s->adaptor.D1(u, v, P, du, dv);
                        put(P, pos + 3 * idx);
                        unit(du, dv, nrm + 3 * idx);
                        break;
                    case OCCT_SLPROPS: {
                        props->SetParameters(u, v);
                        put(props->Value(), pos + 3 * idx);
                        double *n = nrm + 3 * idx;
                        if (props->IsNormalDefined()) {
                            const gp_Dir &d = props->Normal();
                            n[0] = d.X(), n[1] = d.Y(), n[2] = d.Z();
                        } else {
                            n[0] = n[1] = n[2] = 0.0;
                        }
                        bool ok = props->IsCurvatureDefined();
                        K[idx] = ok ? props->GaussianCurvature() : 0.0;
                        H[idx] = ok ? props->MeanCurvature() : 0.0;
                        break;
                    }
                    }
                }
            }
    delete props;
}

static void quiet()
{
    static bool done = false;
    if (!done) { // the data exchange's progress messages would interleave with the tables
        Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
        done = true;
    }
}

extern "C" int occt_write(occt_surf *s, const char *path, int iges)
{
    quiet();
    TopoDS_Face f = BRepBuilderAPI_MakeFace(s->bs, 1e-7);
    if (iges) {
        IGESControl_Writer w("MM", 0);
        if (!w.AddShape(f))
            return -1;
        w.ComputeModel();
        return w.Write(path) ? 0 : -1;
    }
    STEPControl_Writer w;
    if (w.Transfer(f, STEPControl_AsIs) != IFSelect_RetDone)
        return -1;
    return w.Write(path) == IFSelect_RetDone ? 0 : -1;
}

extern "C" int occt_read_poles(const char *path, int iges, int *nu, int *nv)
{
    quiet();
    TopoDS_Shape shape;
    if (iges) {
        IGESControl_Reader r;
        if (r.ReadFile(path) != IFSelect_RetDone)
            return -1;
        r.TransferRoots();
        shape = r.OneShape();
    } else {
        STEPControl_Reader r;
        if (r.ReadFile(path) != IFSelect_RetDone)
            return -1;
        r.TransferRoots();
        shape = r.OneShape();
    }
    int faces = 0;
    *nu = *nv = 0;
    for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next(), faces++) {
        Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(TopoDS::Face(e.Current())));
        if (!b.IsNull() && faces == 0) {
            *nu = b->NbUPoles();
            *nv = b->NbVPoles();
        }
    }
    return faces;
}

// ---- picking ---------------------------------------------------------------------------------

struct occt_proj {
    occt_surf *s;
    GeomAPI_ProjectPointOnSurf proj;
};

extern "C" occt_proj *occt_proj_make(occt_surf *s, int tree)
{
    occt_proj *p = new occt_proj;
    p->s = s;
    double u0, u1, v0, v1;
    s->bs->Bounds(u0, u1, v0, v1);
    p->proj.Init(s->bs, u0, u1, v0, v1, tree ? Extrema_ExtAlgo_Tree : Extrema_ExtAlgo_Grad);
    return p;
}

extern "C" void occt_proj_free(occt_proj *p) { delete p; }

extern "C" int occt_closest(occt_proj *p, const double x[3], double pt[3], double *dist)
{
    try {
        p->proj.Perform(gp_Pnt(x[0], x[1], x[2]));
        if (!p->proj.IsDone() || p->proj.NbPoints() < 1)
            return 0;
        double u, v;
        p->proj.LowerDistanceParameters(u, v);
        gp_Pnt P;
        p->s->bs->D0(u, v, P);
        put(P, pt);
        *dist = p->proj.LowerDistance();
        return 1;
    } catch (const Standard_Failure &) {
        return 0;
    }
}

// The first intersection at line parameter w >= 0 (a length: the line's direction is unit);
// t = w / |d|. 1 hit, 0 none.
static int first_of(int n, double *t, double *pt, double len,
                    const std::function<void(int, double &, gp_Pnt &)> &get)
{
    double best = INFINITY;
    gp_Pnt bp;
    for (int i = 1; i <= n; i++) {
        double w;
        gp_Pnt P;
        get(i, w, P);
        if (w >= 0 && w < best)
            best = w, bp = P;
    }
    if (!(best < INFINITY))
        return 0;
    *t = best / len;
    put(bp, pt);
    return 1;
}

extern "C" int occt_ray_intcs(occt_surf *s, const double o[3], const double d[3], double pt[3], double *t)
{
    try {
        gp_Vec dv(d[0], d[1], d[2]);
        double len = dv.Magnitude();
        Handle(Geom_Line) line = new Geom_Line(gp_Pnt(o[0], o[1], o[2]), gp_Dir(dv));
        GeomAPI_IntCS ics(line, s->bs);
        if (!ics.IsDone())
            return 0;
        return first_of(ics.NbPoints(), t, pt, len, [&](int i, double &w, gp_Pnt &P) {
            double u, v;
            ics.Parameters(i, u, v, w);
            P = ics.Point(i);
        });
    } catch (const Standard_Failure &) {
        return 0;
    }
}

struct occt_rayer {
    occt_surf *s;
    Handle(GeomAdaptor_Surface) hs;
    IntCurveSurface_ThePolyhedronOfHInter *poly;
};

extern "C" occt_rayer *occt_rayer_make(occt_surf *s)
{
    occt_rayer *r = new occt_rayer;
    r->s = s;
    r->hs = new GeomAdaptor_Surface(s->bs);
    double u0, u1, v0, v1;
    s->bs->Bounds(u0, u1, v0, v1);
    // 50 x 50 samples (over 6-8 spans a direction): our choice, kept for every ray
    int nu = 50, nv = 50;
    r->poly = new IntCurveSurface_ThePolyhedronOfHInter(r->hs, nu, nv, u0, v0, u1, v1);
    return r;
}

extern "C" void occt_rayer_free(occt_rayer *r)
{
    if (r)
        delete r->poly;
    delete r;
}

extern "C" int occt_ray_hinter(occt_rayer *r, const double o[3], const double d[3], double pt[3], double *t)
{
    try {
        gp_Vec dv(d[0], d[1], d[2]);
        double len = dv.Magnitude();
        // the line clipped to the poles' box (HInter's polygon needs a bounded curve)
        double w0 = 0, w1 = INFINITY, oo[3] = {o[0], o[1], o[2]}, dd[3] = {d[0] / len, d[1] / len, d[2] / len};
        for (int k = 0; k < 3; k++) {
            if (dd[k] == 0) {
                if (oo[k] < r->s->lo[k] || oo[k] > r->s->hi[k])
                    return 0;
                continue;
            }
            double a = (r->s->lo[k] - oo[k]) / dd[k], b = (r->s->hi[k] - oo[k]) / dd[k];
            w0 = std::max(w0, std::min(a, b));
            w1 = std::min(w1, std::max(a, b));
        }
        if (!(w0 <= w1))
            return 0;
        double pad = 1e-6 * (w1 - w0) + 1e-9;
        Handle(Geom_Line) line = new Geom_Line(gp_Pnt(o[0], o[1], o[2]), gp_Dir(dv));
        Handle(GeomAdaptor_Curve) hc = new GeomAdaptor_Curve(line, std::max(0.0, w0 - pad), w1 + pad);
        IntCurveSurface_HInter h;
        h.Perform(hc, r->hs, *r->poly);
        if (!h.IsDone())
            return 0;
        return first_of(h.NbPoints(), t, pt, len, [&](int i, double &w, gp_Pnt &P) {
            const IntCurveSurface_IntersectionPoint &q = h.Point(i);
            w = q.W();
            P = q.Pnt();
        });
    } catch (const Standard_Failure &) {
        return 0;
    }
}
