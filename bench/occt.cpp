// occt.cpp -- the OpenCASCADE side of rg2_bench: a Geom_BSplineSurface from the same
// poles, weights and knots, evaluated per point through Geom_BSplineSurface, GeomAdaptor_Surface
// (span cache) and GeomLProp_SLProps, and written as one face to STEP and IGES (and rg2's files
// read back). Plain C interface for bench.c.
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

#include <GeomAdaptor_Surface.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cmath>

struct occt_surf {
    Handle(Geom_BSplineSurface) bs;
    GeomAdaptor_Surface adaptor;
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
