// test_crossings.cpp -- OpenCASCADE as an independent judge of rg2 check --intersections: the
// torus pushed through its tube (tests/data/torus_pushed_through.json), written as STEP through
// the library and read back, has self-interference by BOPAlgo_ArgumentAnalyzer (self-
// interference mode only), and rg2_find_crossings finds crossings; the exact torus of the same
// partition (examples/fig1_torus.json, surface 0) has neither.
extern "C" {
#include "../harness.h"
}

#include <BOPAlgo_ArgumentAnalyzer.hxx>
#include <BOPAlgo_CheckResult.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <TopoDS_Shape.hxx>

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace {

// Self-interferences OCCT finds in the STEP of surface k of a design (-1: not read).
int occt_self_interferences(const char *design, int k, const std::string &path, double *seconds)
{
    rg2_design *d = nullptr;
    rg2_error err;
    CHECK_OK(rg2_design_load(design, &d, &err), &err);
    if (!d)
        return -1;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    rg2_status st = rg2_export_file(rg2_design_surface(d, k), 1, path.c_str(), &o, &err);
    CHECK(st == RG2_OK, "%s: export: %s", design, err.msg);
    rg2_crossing_report r;
    CHECK_OK(rg2_find_crossings(rg2_design_surface(d, k), 1, RG2_CROSSING_DEFAULT_DENSITY, 0, &r, &err), &err);
    int ours = r.crossings;
    rg2_design_free(d);
    STEPControl_Reader rd;
    if (st || rd.ReadFile(path.c_str()) != IFSelect_RetDone)
        return -1;
    rd.TransferRoots();
    TopoDS_Shape shape = rd.OneShape();
    auto t0 = std::chrono::steady_clock::now();
    BOPAlgo_ArgumentAnalyzer ana;
    ana.SetShape1(shape);
    ana.ArgumentTypeMode() = Standard_False;
    ana.SelfInterMode() = Standard_True;
    ana.SmallEdgeMode() = Standard_False;
    ana.RebuildFaceMode() = Standard_False;
    ana.TangentMode() = Standard_False;
    ana.MergeVertexMode() = Standard_False;
    ana.MergeEdgeMode() = Standard_False;
    ana.ContinuityMode() = Standard_False;
    ana.CurveOnSurfaceMode() = Standard_False;
    ana.Perform();
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int n = 0;
    for (const BOPAlgo_CheckResult &c : ana.GetCheckResult())
        n += c.GetCheckStatus() == BOPAlgo_SelfIntersect;
    printf("%s surface %d: OCCT %d self-interferences (%.2f s), rg2 %d crossing pairs\n", design, k, n, *seconds, ours);
    CHECK((n > 0) == (ours > 0), "%s: OCCT %d self-interferences, rg2 %d crossings", design, n, ours);
    unlink(path.c_str());
    return n;
}

} // namespace

int main()
{
    char dir[] = "/tmp/rg2_occt_crossXXXXXX";
    if (!mkdtemp(dir))
        return 1;
    double t1 = 0, t2 = 0;
    int pushed = occt_self_interferences("tests/data/torus_pushed_through.json", 0, std::string(dir) + "/p.step", &t1);
    int clean = occt_self_interferences("examples/fig1_torus.json", 0, std::string(dir) + "/c.step", &t2);
    CHECK(pushed > 0, "OCCT finds the pushed torus self-interfering (%d)", pushed);
    CHECK(clean == 0, "OCCT finds the exact torus clean (%d)", clean);
    rmdir(dir);
    return rg2t_done("occt_test_crossings");
}
