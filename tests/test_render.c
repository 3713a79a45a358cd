/* test_render.c -- per-pixel exact pictures: the exact data behind each pixel (sphere: the
 * mean curvature is constant, normals are unit, points lie on the sphere), zebra stripes kink
 * across a G1 seam and not across G2 seams, PNG output decodes, output is deterministic.
 * The sphere checks run again with a mixed pattern of patches replaced by their exact degree
 * elevations (xmix.h), and pictures of such surfaces are compared with the bi-3 ones.
 * Set RG2_KEEP_PICTURES=dir to keep the PNGs for looking at them. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, symlink */
#include "harness.h"
#include "scenes.h"
#include "xmix.h"

#include <errno.h>
#include <sys/stat.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *keep_dir(void) { return getenv("RG2_KEEP_PICTURES"); }

/* Write img to a temporary (or kept) PNG; returns the path in buf. */
static const char *png_path(const char *name, char *buf, size_t len)
{
    const char *dir = keep_dir();
    if (dir)
        snprintf(buf, len, "%s/%s.png", dir, name);
    else
        snprintf(buf, len, "/tmp/rg2_test_render_%ld_%s.png", (long)getpid(), name);
    return buf;
}

static void done_png(const char *path)
{
    if (!keep_dir())
        remove(path);
}

/* Decode a PNG with libpng: size, colour type, bit depth; pixels into *rgb (malloc'd). */
static int read_png(const char *path, int *w, int *h, int *ctype, int *depth, unsigned char **rgb)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    unsigned char *volatile data = NULL;
    png_bytep *volatile rows = NULL;
    volatile int ok = 0;
    if (setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, f);
        png_read_info(png, info);
        *w = (int)png_get_image_width(png, info);
        *h = (int)png_get_image_height(png, info);
        *ctype = png_get_color_type(png, info);
        *depth = png_get_bit_depth(png, info);
        if (*ctype == PNG_COLOR_TYPE_RGB && *depth == 8) {
            data = malloc((size_t)*w * *h * 3);
            rows = malloc((size_t)*h * sizeof *rows);
            for (int y = 0; y < *h; y++)
                rows[y] = data + (size_t)y * *w * 3;
            png_read_image(png, rows);
            png_read_end(png, NULL);
        }
        ok = 1;
    }
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    free(rows);
    *rgb = data;
    return ok;
}

/* Sphere band (radius 1, latitudes -60..60 degrees): every pixel's exact data. */
static void sphere_pixels(int mixed)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 6, 4, 0, -M_PI / 3, M_PI / 6, &m, &s, &err), &err);
    if (mixed)
        CHECK_OK(xmix_elevate(&s, &err), &err);
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    o.width = 160;
    o.height = 120;
    o.mode = RG2_RENDER_MEAN;
    o.keep_pixels = 1;
    rg2_image img;
    CHECK_OK(rg2_render(&s, 1, &m, &o, &img, &err), &err);
    double worstH = 0, worstN = 0, worstR = 0, worstRes = 0, H0 = 0;
    int fg = 0;
    for (int k = 0; k < img.width * img.height; k++) {
        const rg2_pixel *p = &img.pixels[k];
        if (p->surf < 0)
            continue;
        if (!fg)
            H0 = p->H;
        fg++;
        worstH = fmax(worstH, fabs(fabs(p->H) - 1.0));
        worstH = fmax(worstH, fabs(p->H - H0));
        worstN = fmax(worstN, fabs(sqrt(p->n[0] * p->n[0] + p->n[1] * p->n[1] + p->n[2] * p->n[2]) - 1.0));
        worstR = fmax(worstR, fabs(sqrt(p->p[0] * p->p[0] + p->p[1] * p->p[1] + p->p[2] * p->p[2]) - 1.0));
        worstRes = fmax(worstRes, p->resid);
    }
    printf("sphere band %dx%d%s: %d foreground pixels, %d refined; |H| - 1: %.2e, |n| - 1: %.2e, "
           "|p| - 1: %.2e, ray residual %.2e\n",
           img.width, img.height, mixed ? " (mixed degrees)" : "", fg, img.refined, worstH, worstN, worstR, worstRes);
    CHECK(fg > 2000, "sphere covers %d pixels", fg);
    CHECK(img.refined >= fg * 95 / 100, "Newton converged at %d of %d pixels", img.refined, fg);
    CHECK(worstH <= 1e-12, "mean curvature per pixel constant to %.3g", worstH);
    CHECK(worstN <= 1e-14, "normals unit to %.3g", worstN);
    CHECK(worstR <= 1e-13, "pixel points on the sphere to %.3g", worstR);
    CHECK(img.range[0] < H0 && H0 < img.range[1], "colour range [%g, %g] holds H = %g", img.range[0],
          img.range[1], H0);
    rg2_image_free(&img);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* A whole sphere from a closed v circle (patch edges collapse to the poles, where the normal
 * is undefined): the picture still resolves every pixel to a finite point on the sphere. */
static void sphere_poles(int mixed)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 4, 4, 1, 0, 0, &m, &s, &err), &err);
    if (mixed)
        CHECK_OK(xmix_elevate(&s, &err), &err);
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    o.width = 96;
    o.height = 96;
    o.elevation = 80; /* look almost down onto a pole */
    o.mode = RG2_RENDER_GAUSS;
    o.keep_pixels = 1;
    rg2_image img;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
    int fg = 0, bad = 0;
    double worstR = 0, worstK = 0;
    for (int k = 0; k < img.width * img.height; k++) {
        const rg2_pixel *p = &img.pixels[k];
        if (p->surf < 0)
            continue;
        fg++;
        if (!isfinite(p->K) || !isfinite(p->phase) || !isfinite(p->p[0]))
            bad++;
        worstR = fmax(worstR, fabs(sqrt(p->p[0] * p->p[0] + p->p[1] * p->p[1] + p->p[2] * p->p[2]) - 1.0));
        if (p->n[0] != 0 || p->n[1] != 0 || p->n[2] != 0)
            worstK = fmax(worstK, fabs(p->K - 1.0));
    }
    printf("sphere with poles%s: %d pixels, %d non-finite, |p| - 1 %.2e, K - 1 %.2e\n", mixed ? " (mixed degrees)" : "",
           fg, bad, worstR, worstK);
    CHECK(fg > 2000 && bad == 0, "%d pixels, %d non-finite", fg, bad);
    CHECK(worstR <= 1e-13, "points on the sphere to %.3g", worstR);
    CHECK(worstK <= 1e-9, "Gaussian curvature 1 to %.3g where the normal is defined", worstK);
    char path[512];
    if (keep_dir())
        rg2_image_write_png(&img, png_path("sphere_poles", path, sizeof path), &err);
    rg2_image_free(&img);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Wrap a phase difference into (-pi, pi]. */
static double wrap(double a)
{
    while (a > M_PI)
        a -= 2 * M_PI;
    while (a <= -M_PI)
        a += 2 * M_PI;
    return a;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Stripe-kink statistic: along each image row, where the patch changes between pixels x and
 * x + 1 (same surface, three pixels of each patch on either side), the one-sided phase slopes
 * s(-2), s(-1) left and s(1), s(2) right (s(k) = phi(x+k+1) - phi(x+k), s(-1) = phi(x) -
 * phi(x-1)). The slope jump across the seam beyond the local trend,
 *   |s(1) - s(-1) - ((s(-1) - s(-2)) + (s(2) - s(1)))|,
 * relative to max(|s(-1)|, |s(1)|), median over the rows. A G1 seam's curvature jump makes the
 * stripe direction jump; across a G2 seam the slope changes smoothly. */
static double stripe_kink(const rg2_image *img, int *count)
{
    int W = img->width;
    double *vals = malloc(sizeof(double) * (size_t)img->height * 8);
    int n = 0;
    for (int y = 0; y < img->height; y++)
        for (int x = 2; x + 3 < W; x++) {
            const rg2_pixel *p = &img->pixels[(size_t)y * W + x - 2];
            int ok = 1;
            for (int k = 0; k < 6; k++)
                ok &= p[k].surf == p[0].surf && p[k].surf >= 0 && p[k].patch == (k < 3 ? p[0].patch : p[5].patch);
            if (!ok || p[0].patch == p[5].patch)
                continue;
            double sm2 = wrap(p[1].phase - p[0].phase), sm1 = wrap(p[2].phase - p[1].phase);
            double s1 = wrap(p[4].phase - p[3].phase), s2 = wrap(p[5].phase - p[4].phase);
            double jump = fabs(s1 - sm1 - ((sm1 - sm2) + (s2 - s1)));
            double den = fmax(fabs(sm1), fabs(s1));
            if (den > 0 && n < img->height * 8)
                vals[n++] = jump / den;
        }
    double med = 0;
    if (n) {
        qsort(vals, (size_t)n, sizeof *vals, cmp_d);
        med = vals[n / 2];
    }
    free(vals);
    *count = n;
    return med;
}

static void zebra_kinks(void)
{
    rg2_surface g1, g2;
    rg2_mesh m2;
    rg2_error err;
    CHECK_OK(scene_cyl_plane(1.0, 1.6, 2.0, &g1, &err), &err);
    CHECK_OK(scene_bspline_profile(1.0, 1.6, 2.0, &m2, &g2, &err), &err);
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    o.width = 240;
    o.height = 180;
    o.mode = RG2_RENDER_ZEBRA;
    o.azimuth = -90;
    o.elevation = 55;
    o.stripes = 24;
    o.keep_pixels = 1;
    rg2_image a, b;
    CHECK_OK(rg2_render(&g1, 1, NULL, &o, &a, &err), &err);
    CHECK_OK(rg2_render(&g2, 1, &m2, &o, &b, &err), &err);
    int na, nb;
    double ka = stripe_kink(&a, &na), kb = stripe_kink(&b, &nb);
    rg2t_seams sa, sb;
    rg2t_surface_seams(&g1, 16, &sa);
    rg2t_surface_seams(&g2, 16, &sb);
    printf("zebra stripe kink (median |slope jump| / slope at seam pixels): G1 cylinder+plane %.3f "
           "(%d rows), G2 B-spline %.4f (%d seam pixels); measured curvature jumps %.3g vs %.3g\n",
           ka, na, kb, nb, sa.curv, sb.curv);
    CHECK(na >= 50 && nb >= 50, "seam pixels found: %d, %d", na, nb);
    CHECK(ka > 0.2, "G1 seam kinks the stripes: %.3g", ka);
    CHECK(kb < 0.05, "G2 seams do not kink the stripes: %.3g", kb);
    CHECK(ka > 8 * kb, "the statistic separates G1 (%.3g) from G2 (%.3g)", ka, kb);
    CHECK(sa.curv > 0.5 && sb.curv < 1e-10, "the seams are G1 (%.3g) and G2 (%.3g)", sa.curv, sb.curv);
    char path[512];
    if (keep_dir()) {
        rg2_image_write_png(&a, png_path("zebra_g1", path, sizeof path), &err);
        rg2_image_write_png(&b, png_path("zebra_g2", path, sizeof path), &err);
    }
    rg2_image_free(&a);
    rg2_image_free(&b);
    rg2_surface_free(&g1);
    rg2_surface_free(&g2);
    rg2_mesh_free(&m2);
}

/* PNG: decodes with libpng as 8-bit RGB of the requested size, same pixels as rendered. */
static void png_valid_and_deterministic(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    static const rg2_render_mode modes[4] = {RG2_RENDER_SHADED, RG2_RENDER_MEAN, RG2_RENDER_GAUSS, RG2_RENDER_ZEBRA};
    static const char *names[4] = {"torus_shaded", "torus_mean", "torus_gauss", "torus_zebra"};
    for (int q = 0; q < 4; q++) {
        rg2_render_opts o;
        rg2_render_opts_default(&o);
        o.width = 200 + q;
        o.height = 130;
        o.mode = modes[q];
        o.boundaries = q == 0;
        o.mesh = q == 0;
        rg2_image one, two;
        o.threads = 1;
        CHECK_OK(rg2_render(&s, 1, &m, &o, &one, &err), &err);
        o.threads = 2;
        CHECK_OK(rg2_render(&s, 1, &m, &o, &two, &err), &err);
        size_t nbytes = (size_t)one.width * one.height * 3;
        CHECK(two.rgb && one.rgb && !memcmp(one.rgb, two.rgb, nbytes), "%s: 1 and 2 threads give the same bytes",
              names[q]);
        char path[512];
        png_path(names[q], path, sizeof path);
        CHECK_OK(rg2_image_write_png(&one, path, &err), &err);
        int w = 0, h = 0, ct = -1, bd = 0;
        unsigned char *rgb = NULL;
        CHECK(read_png(path, &w, &h, &ct, &bd, &rgb), "%s decodes", path);
        CHECK(w == o.width && h == o.height && ct == PNG_COLOR_TYPE_RGB && bd == 8,
              "%s: %dx%d colour type %d depth %d", names[q], w, h, ct, bd);
        CHECK(rgb && !memcmp(rgb, one.rgb, nbytes), "%s: decoded pixels equal the rendered ones", names[q]);
        /* a picture, not a blank: the surface covers a good part and has many tones */
        int tones[256] = {0}, distinct = 0;
        for (size_t k = 0; k < nbytes; k += 3)
            tones[one.rgb[k + 1]] = 1;
        for (int k = 0; k < 256; k++)
            distinct += tones[k];
        CHECK(one.foreground > one.width * one.height / 5 && distinct > 40, "%s: %d surface pixels, %d green levels",
              names[q], one.foreground, distinct);
        free(rgb);
        done_png(path);
        rg2_image_free(&one);
        rg2_image_free(&two);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* A torus picture of a surface with elevated patches against the bi-3 original (every mode,
 * boundaries and mesh overlaid): the same pixels resolve to the same patch, the exact data
 * agree to rounding, the bytes agree but for pixels where rounding tips a colour level, and 1
 * and 2 threads give the same bytes. */
static void mixed_vs_plain(void)
{
    rg2_mesh m;
    rg2_surface s, x;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    CHECK_OK(xmix_copy(&s, &x, &err), &err);
    static const rg2_render_mode modes[4] = {RG2_RENDER_SHADED, RG2_RENDER_MEAN, RG2_RENDER_GAUSS, RG2_RENDER_ZEBRA};
    for (int q = 0; q < 4; q++) {
        rg2_render_opts o;
        rg2_render_opts_default(&o);
        o.width = 180;
        o.height = 120;
        o.mode = modes[q];
        o.boundaries = q == 0;
        o.mesh = q == 0;
        o.keep_pixels = 1;
        o.threads = 1;
        rg2_image a, b, b2;
        CHECK_OK(rg2_render(&s, 1, &m, &o, &a, &err), &err);
        CHECK_OK(rg2_render(&x, 1, &m, &o, &b, &err), &err);
        o.threads = 2;
        CHECK_OK(rg2_render(&x, 1, &m, &o, &b2, &err), &err);
        size_t np = (size_t)a.width * a.height;
        int other_patch = 0, bytes = 0, maxbyte = 0;
        double dp = 0, dn = 0, dH = 0, dK = 0;
        for (size_t k = 0; k < np; k++) {
            const rg2_pixel *p = &a.pixels[k], *r = &b.pixels[k];
            if (p->surf != r->surf || p->patch != r->patch) {
                other_patch++;
                continue;
            }
            if (p->surf < 0)
                continue;
            for (int c = 0; c < 3; c++) {
                dp = fmax(dp, fabs(p->p[c] - r->p[c]) / 8.0);
                dn = fmax(dn, fabs(p->n[c] - r->n[c]));
            }
            dH = fmax(dH, fabs(p->H - r->H));
            dK = fmax(dK, fabs(p->K - r->K));
        }
        for (size_t k = 0; k < 3 * np; k++) {
            int d = abs((int)a.rgb[k] - (int)b.rgb[k]);
            bytes += d != 0;
            maxbyte = d > maxbyte ? d : maxbyte;
        }
        printf("torus mode %d, %d of 48 patches elevated vs bi-3: %d of %zu pixels on another patch, exact data p %.1e "
               "n %.1e H %.1e K %.1e, %d bytes differ (by <= %d), threads 1/2 %s\n",
               q, xmix_count(&x), other_patch, np, dp, dn, dH, dK, bytes, maxbyte,
               b2.rgb && !memcmp(b.rgb, b2.rgb, 3 * np) ? "identical" : "differ");
        CHECK(a.foreground == b.foreground && other_patch <= (int)(np / 1000),
              "mode %d: foreground %d vs %d, %d pixels on another patch", q, a.foreground, b.foreground, other_patch);
        /* both pixel points lie on the pixel ray to the Newton tolerance, 1e-12 of the scene */
        CHECK(dp <= 1e-12 && dn <= 1e-11 && dH <= 1e-11 && dK <= 1e-11, "mode %d: exact data p %.3g n %.3g H %.3g K %.3g",
              q, dp, dn, dH, dK);
        CHECK(bytes <= (int)(3 * np / 1000) && maxbyte <= 2, "mode %d: %d bytes differ, by up to %d", q, bytes, maxbyte);
        CHECK(b2.rgb && !memcmp(b.rgb, b2.rgb, 3 * np), "mode %d: 1 and 2 threads give the same bytes", q);
        rg2_image_free(&a);
        rg2_image_free(&b);
        rg2_image_free(&b2);
    }
    rg2_surface_free(&x);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The general-quadratic saddle cap of Fig. 15 (degree (5,3) cap patches): pixels on the cap
 * patches carry the exact data of the patch at their (u, v) (point, normal, H, K equal to
 * rg2_surface_eval there), Newton reaches the pixel ray, and the picture with every patch
 * elevated to (5,5) is the same. */
static void design_caps(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/fig15_saddle_caps.json", &d, &err), &err);
    if (!d)
        return;
    const rg2_surface *s = rg2_design_surface(d, 1);
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    o.width = 240;
    o.height = 180;
    o.mode = RG2_RENDER_MEAN;
    o.elevation = -89; /* from below: the cap is the south end, around (3, 0, 0) */
    o.keep_pixels = 1;
    rg2_image img, ix;
    CHECK_OK(rg2_render(s, 1, NULL, &o, &img, &err), &err);
    int cap = 0, conv = 0, fg = 0;
    double dev = 0, devc = 0, scale = rg2t_surface_scale(s);
    for (int k = 0; k < img.width * img.height; k++) {
        const rg2_pixel *p = &img.pixels[k];
        if (p->surf < 0)
            continue;
        fg++;
        int i = p->patch / s->nv, j = p->patch % s->nv;
        if (j >= 3 || !rg2_surface_xpatch(s, i, j)) /* the cap: the first three rows, degree (5,3) */
            continue;
        cap++;
        conv += p->resid <= 1e-12 * scale;
        rg2_eval e;
        rg2_surface_eval(s, i, j, p->u, p->v, 2, &e);
        for (int c = 0; c < 3; c++)
            dev = fmax(dev, fmax(fabs(e.p[c] - p->p[c]) / scale, fabs(e.n[c] - p->n[c])));
        devc = fmax(devc, fmax(fabs(e.H - p->H), fabs(e.K - p->K)));
    }
    o.threads = 2;
    rg2_surface x;
    CHECK_OK(xmix_raise_copy(s, 5, 5, &x, &err), &err);
    CHECK_OK(rg2_render(&x, 1, NULL, &o, &ix, &err), &err);
    int other = 0;
    for (int k = 0; k < img.width * img.height; k++)
        other += img.pixels[k].surf != ix.pixels[k].surf || img.pixels[k].patch != ix.pixels[k].patch;
    printf("Fig. 15 general cap: %d of %d pixels on the degree-(5,3) cap patches, %d on the ray to 1e-12, exact data = "
           "rg2_surface_eval to %.1e (H, K %.1e); every patch elevated to (5,5): %d pixels on another patch\n",
           cap, fg, conv, dev, devc, other);
    CHECK(cap > 500 && conv >= cap * 95 / 100, "%d cap pixels, %d converged", cap, conv);
    CHECK(dev == 0 && devc == 0, "pixel data = the patch evaluation at its (u, v): %.3g, %.3g", dev, devc);
    CHECK(other <= img.width * img.height / 1000, "%d pixels on another patch at degree (5,5)", other);
    rg2_image_free(&img);
    rg2_image_free(&ix);
    rg2_surface_free(&x);
    rg2_design_free(d);
}

static void errors(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 4, 4, 1, 0, 0, &m, &s, &err), &err);
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    rg2_image img;
    CHECK(rg2_render(&s, 0, NULL, &o, &img, &err) == RG2_EINVAL && strstr(err.msg, "no surfaces"), "%s", err.msg);
    o.width = 4;
    CHECK(rg2_render(&s, 1, NULL, &o, &img, &err) == RG2_EINVAL && strstr(err.msg, "4 x 600"), "%s", err.msg);
    o.width = 64;
    o.mesh = 1;
    CHECK(rg2_render(&s, 1, NULL, &o, &img, &err) == RG2_EINVAL && strstr(err.msg, "mesh"), "%s", err.msg);
    o.mesh = 0;
    o.range_set = 1;
    o.range[0] = 2;
    o.range[1] = 1;
    CHECK(rg2_render(&s, 1, NULL, &o, &img, &err) == RG2_EINVAL && strstr(err.msg, "range"), "%s", err.msg);
    o.range_set = 0;
    s.patch[5].h[1][2][0] = NAN;
    CHECK(rg2_render(&s, 1, NULL, &o, &img, &err) == RG2_ENONFINITE && strstr(err.msg, "patch (1,1)"), "%s",
          err.msg);
    s.patch[5].h[1][2][0] = 0;
    /* a higher-degree patch: its own control points are checked, the unused bi-3 slot is not */
    CHECK_OK(rg2t_elevate_some(&s, 5, 3, 16, 7, &err), &err);
    s.xp[7].h[4][2][3] = INFINITY;
    CHECK(rg2_render(&s, 1, NULL, &o, &img, &err) == RG2_ENONFINITE && strstr(err.msg, "patch (1,3)"), "%s",
          err.msg);
    s.xp[7].h[4][2][3] = 1;
    s.xp[7].h[5][3][1] = NAN;
    CHECK(rg2_render(&s, 1, NULL, &o, &img, &err) == RG2_ENONFINITE && strstr(err.msg, "patch (1,3)"),
          "degree-5 row checked: %s", err.msg);
    s.xp[7].du = 0; /* back to the bi-3 slot, which the elevation filled with NaN */
    CHECK(rg2_render(&s, 1, NULL, &o, &img, &err) == RG2_ENONFINITE && strstr(err.msg, "patch (1,3)"), "%s",
          err.msg);
    free(s.xp);
    s.xp = NULL;
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    CHECK_OK(scene_revolve(3.0, 1.0, 4, 4, 1, 0, 0, &m, &s, &err), &err);
    o.width = 32;
    o.height = 32;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
    CHECK(rg2_image_write_png(&img, "/nonexistent-dir/x.png", &err) == RG2_EIO && strstr(err.msg, "nonexistent"),
          "%s", err.msg);
    /* a full disk: files fail past 100 bytes (EFBIG), so libpng's writes fail.
     * The error names the reason, nothing is printed (stderr to a file meanwhile), nothing is
     * left behind. */
    char dir[] = "/tmp/rg2-png-XXXXXX";
    if (mkdtemp(dir)) {
        char png_out[64], log[80];
        snprintf(png_out, sizeof png_out, "%s/x.png", dir);
        snprintf(log, sizeof log, "%s/stderr", dir);
        fflush(stderr);
        int saved = dup(2);
        FILE *lf = fopen(log, "w");
        dup2(fileno(lf), 2);
        rg2_image big = {.width = 128, .height = 128, .rgb = malloc(128 * 128 * 3)}; /* noise: */
        unsigned x = 2463534242u; /* xorshift noise: 48 KB that do not compress, past stdio's buffer */
        for (int k = 0; big.rgb && k < 128 * 128 * 3; k++) {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            big.rgb[k] = (unsigned char)(x >> 24);
        }
        CHECK(rg2t_file_limit(100) == 0, "file size limit");
        rg2_status st = rg2_image_write_png(&big, png_out, &err);
        rg2t_file_limit(-1);
        free(big.rgb);
        fflush(stderr);
        dup2(saved, 2);
        close(saved);
        fclose(lf);
        struct stat sb;
        long printed = stat(log, &sb) == 0 ? (long)sb.st_size : -1;
        CHECK(st == RG2_EIO && strstr(err.msg, "x.png") && strstr(err.msg, strerror(EFBIG)),
              "full disk: %s", err.msg);
        CHECK(printed == 0, "full disk: the library printed %ld bytes to stderr", printed);
        remove(log);
        CHECK(access(png_out, F_OK) != 0 && rmdir(dir) == 0, "full disk: something left behind in %s", dir);
    }
    rg2_image_free(&img);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Options that change what a picture shows, each against a picture it must equal or differ from:
 * a colour range given equal to the robust one gives the same bytes; two ranges above every H
 * clamp every surface pixel to the same colour (only their bar labels differ); the Gaussian
 * colour bar is the diverging map itself (blue at the bottom, grey in the middle, red at the
 * top); tint 0 is the picture of the untagged surface. And the option checks, by message. */
static void options(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 6, 4, 1, 0, 0, &m, &s, &err), &err);
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    o.width = 240; /* > 2 x 110: room for the colour bar */
    o.height = 160;
    o.mode = RG2_RENDER_MEAN;
    o.keep_pixels = 1;
    rg2_image a, b, c;
    size_t nb = (size_t)o.width * o.height * 3;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &a, &err), &err);
    double hmax = -HUGE_VAL;
    for (int k = 0; a.pixels && k < o.width * o.height; k++)
        if (a.pixels[k].surf >= 0)
            hmax = fmax(hmax, a.pixels[k].H);
    o.keep_pixels = 0;
    o.range_set = 1;
    o.range[0] = a.range[0];
    o.range[1] = a.range[1];
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &b, &err), &err);
    CHECK(b.range[0] == a.range[0] && b.range[1] == a.range[1] && !memcmp(a.rgb, b.rgb, nb),
          "the robust range [%g, %g] given as the range: another picture", a.range[0], a.range[1]);
    rg2_image_free(&b);
    o.range[0] = hmax + 1;
    o.range[1] = hmax + 2;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &b, &err), &err);
    o.range[0] = hmax + 5;
    o.range[1] = hmax + 50;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &c, &err), &err);
    int vw = o.width - 110, same = 1, bar_same = 1, fg = 0;
    for (int y = 0; y < o.height; y++)
        for (int x = 0; x < o.width; x++) {
            size_t k = 3 * ((size_t)y * o.width + x);
            int eq = !memcmp(b.rgb + k, c.rgb + k, 3);
            if (x < vw) {
                same = same && eq;
                fg += a.pixels[(size_t)y * o.width + x].surf >= 0;
            } else
                bar_same = bar_same && eq;
        }
    CHECK(b.range[0] == hmax + 1 && b.range[1] == hmax + 2 && c.range[0] == hmax + 5 && c.range[1] == hmax + 50,
          "ranges given: [%g, %g], [%g, %g]", b.range[0], b.range[1], c.range[0], c.range[1]);
    CHECK(fg > 1000 && same && !bar_same, "two ranges above H max %g: surface pixels the same %d (of %d), bar labels "
                                          "differ %d", hmax, same, fg, !bar_same);
    CHECK(memcmp(a.rgb, b.rgb, nb) != 0, "a range above every H leaves the picture unchanged");
    rg2_image_free(&a);
    rg2_image_free(&b);
    rg2_image_free(&c);

    /* the Gaussian colour bar: rows 40 (t = 1) .. height - 40 (t = 0), columns vw + 12 .. + 33 */
    o.range_set = 0;
    o.mode = RG2_RENDER_GAUSS;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &a, &err), &err);
    static const double blue[3] = {0.23, 0.30, 0.75}, grey[3] = {0.87, 0.87, 0.87}, red[3] = {0.71, 0.02, 0.15};
    const int rows[3] = {o.height - 40, (o.height - 40 + 40) / 2, 40};
    const double *want[3] = {blue, grey, red};
    int bar_ok = 1;
    for (int q = 0; q < 3; q++)
        for (int x = vw + 12; x < vw + 12 + 22; x++)
            for (int k = 0; k < 3; k++)
                bar_ok = bar_ok && a.rgb[3 * ((size_t)rows[q] * o.width + x) + k] == (unsigned char)lround(255 * want[q][k]);
    CHECK(bar_ok, "Gaussian colour bar: not the diverging map blue / grey / red at rows %d, %d, %d", rows[0], rows[1],
          rows[2]);
    o.colorbar = 0;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &b, &err), &err);
    int bar_gone = 1;
    for (int x = vw + 12; x < vw + 12 + 22; x++)
        bar_gone = bar_gone && memcmp(b.rgb + 3 * ((size_t)rows[1] * o.width + x), a.rgb + 3 * ((size_t)rows[1] * o.width + x), 3);
    CHECK(bar_gone, "colorbar 0: the bar is still drawn");
    rg2_image_free(&a);
    rg2_image_free(&b);
    o.colorbar = 1;

    /* tint: a tagged surface untinted is the untagged surface */
    o.mode = RG2_RENDER_SHADED;
    s.tag = calloc((size_t)s.nu * s.nv, sizeof(int)); /* every patch exact on shape 0 */
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &a, &err), &err);
    o.tint = 0;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &b, &err), &err);
    free(s.tag);
    s.tag = NULL;
    o.tint = 1;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &c, &err), &err);
    CHECK(memcmp(a.rgb, b.rgb, nb) != 0 && !memcmp(b.rgb, c.rgb, nb),
          "tint 0: tinted picture unchanged %d, untinted differs from the untagged surface's %d",
          !memcmp(a.rgb, b.rgb, nb), memcmp(b.rgb, c.rgb, nb) != 0);
    rg2_image_free(&a);
    rg2_image_free(&b);
    rg2_image_free(&c);

    /* straight down and straight up (elevation +-90: the view's up is y): the torus about z is
     * a ring around the image centre, the same mask turned by 90 degrees (an exact torus of
     * revolution in a square image), seen from below the mirror image of the view from above
     * (up to the few silhouette pixels whose centres the exact outline passes within rounding) */
    rg2_render_opts_default(&o);
    o.width = o.height = 64;
    o.keep_pixels = 1;
    rg2_image top, bottom;
    o.elevation = 90;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &top, &err), &err);
    o.elevation = -90;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &bottom, &err), &err);
    int W = 64, rot_diff = 0, mx = 0, my = 0, ring = 0;
    for (int y = 0; top.pixels && bottom.pixels && y < W; y++)
        for (int x = 0; x < W; x++) {
            int f = top.pixels[y * W + x].surf >= 0;
            rot_diff += f != (top.pixels[x * W + (W - 1 - y)].surf >= 0);
            my += f != (bottom.pixels[(W - 1 - y) * W + x].surf >= 0);
            mx += f != (bottom.pixels[y * W + (W - 1 - x)].surf >= 0);
            ring += f;
        }
    int hole = top.pixels && top.pixels[32 * W + 32].surf < 0 && top.pixels[31 * W + 31].surf < 0;
    int mirror_diff = mx < my ? mx : my;
    CHECK(top.pixels && ring > 500 && hole && rot_diff <= 16 && mirror_diff <= 16,
          "torus from straight above: %d ring pixels, hole %d, %d differ turned by 90 degrees, %d / %d from below "
          "mirrored in x / y",
          ring, hole, rot_diff, mx, my);
    printf("torus from straight above / below: %d ring pixels, %d / %d mask pixels off the symmetries\n", ring,
           rot_diff, mirror_diff);
    rg2_image_free(&top);
    rg2_image_free(&bottom);

    /* option checks */
    struct {
        int field;
        double value;
        rg2_status code;
        const char *msg;
    } bad[] = {{0, 9, RG2_EINVAL, "render: unknown mode 9"},
               {1, 0.5, RG2_EINVAL, "render: field of view 0.5 outside (1, 170) degrees"},
               /* the edges rg2.h gives (fov strictly between 1 and 170, stripes 1..1000, a NaN view
                * RG2_ENONFINITE): the comments gave no fov or stripes range and no ENONFINITE */
               {1, 1, RG2_EINVAL, "render: field of view 1 outside (1, 170) degrees"},
               {1, 170, RG2_EINVAL, "render: field of view 170 outside (1, 170) degrees"},
               {1, NAN, RG2_EINVAL, "render: field of view nan outside (1, 170) degrees"},
               {6, NAN, RG2_ENONFINITE, "render: elevation nan is not a finite number"},
               {5, 1000.5, RG2_EINVAL, "render: stripes 1000.5 outside 1..1000"},
               {5, 0.99, RG2_EINVAL, "render: stripes 0.99 outside 1..1000"},
               {4, -0.01, RG2_EINVAL, "render: percentile -0.01 outside [0, 0.5)"},
               {2, NAN, RG2_ENONFINITE, "render: azimuth nan is not a finite number"},
               {3, INFINITY, RG2_ENONFINITE, "render: distance inf is not a finite number"},
               {4, 0.5, RG2_EINVAL, "render: percentile 0.5 outside [0, 0.5)"},
               {5, 0, RG2_EINVAL, "render: stripes 0 outside 1..1000"},
               {6, 95, RG2_EINVAL, "render: elevation 95 outside [-90, 90] degrees"},
               {6, -90.5, RG2_EINVAL, "render: elevation -90.5 outside [-90, 90] degrees"},
               {7, -1, RG2_EINVAL, "render: threads -1 outside 0..1024 (0: the OpenMP default)"},
               /* 100000 threads overflowed the stack inside OpenMP */
               {7, 100000, RG2_EINVAL, "render: threads 100000 outside 0..1024"},
               /* a range whose width overflows painted the surface one colour */
               {8, 1e308, RG2_EINVAL, "render: colour range -1e+308,1e+308 is wider than the largest double"}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        rg2_render_opts_default(&o);
        o.width = o.height = 32;
        switch (bad[k].field) {
        case 0: o.mode = (rg2_render_mode)(int)bad[k].value; break;
        case 1: o.fov = bad[k].value; break;
        case 2: o.azimuth = bad[k].value; break;
        case 3: o.distance = bad[k].value; break;
        case 4: o.percentile = bad[k].value; break;
        case 6: o.elevation = bad[k].value; break;
        case 7: o.threads = (int)bad[k].value; break;
        case 8:
            o.mode = RG2_RENDER_GAUSS, o.range_set = 1;
            o.range[0] = -bad[k].value, o.range[1] = bad[k].value;
            break;
        default: o.mode = RG2_RENDER_ZEBRA, o.stripes = bad[k].value; break;
        }
        rg2_status st = rg2_render(&s, 1, NULL, &o, &a, &err);
        CHECK(st == bad[k].code && strstr(err.msg, bad[k].msg), "bad option %zu: %s '%s', want '%s'", k,
              rg2_status_str(st), err.msg, bad[k].msg);
    }
    /* the insides of those edges render; stripes are checked in zebra mode only (as rg2.h says) */
    for (int k = 0; k < 4; k++) {
        rg2_image e;
        rg2_render_opts_default(&o);
        o.width = o.height = 16;
        if (k == 0)
            o.fov = 1.5;
        else if (k == 1)
            o.fov = 169.5;
        else if (k == 2)
            o.mode = RG2_RENDER_ZEBRA, o.stripes = 1000, o.elevation = -90;
        else
            o.stripes = 0; /* shaded: not read */
        rg2_status st = rg2_render(&s, 1, NULL, &o, &e, &err);
        CHECK(st == RG2_OK, "in-range options %d: %s %s", k, rg2_status_str(st), st ? err.msg : "");
        rg2_image_free(&e);
    }
    /* an azimuth of 1e308 degrees is the angle fmod(1e308, 360): the same picture, not an empty
     * one (the angle in radians overflowed to inf) */
    {
        rg2_image h, r;
        rg2_render_opts_default(&o);
        o.width = o.height = 32;
        o.keep_pixels = 1;
        o.azimuth = 1e308;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &h, &err), &err);
        o.azimuth = fmod(1e308, 360.0);
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &r, &err), &err);
        int alike = h.rgb && r.rgb && !memcmp(h.rgb, r.rgb, 32 * 32 * 3), surface_px = 0;
        for (int k = 0; h.pixels && k < 32 * 32; k++)
            surface_px += h.pixels[k].surf >= 0;
        CHECK(alike && surface_px > 0, "azimuth 1e308: %s the picture at %.17g degrees, %d surface pixels",
              alike ? "the same as" : "differs from", fmod(1e308, 360.0), surface_px);
        rg2_image_free(&h);
        rg2_image_free(&r);
    }
    /* threads 0..1024: the largest count is a render like any other (at most 64 threads run),
     * the bytes of one thread */
    {
        rg2_image one, most;
        rg2_render_opts_default(&o);
        o.width = o.height = 32;
        o.threads = 1;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &one, &err), &err);
        o.threads = 1024;
        rg2_status st = rg2_render(&s, 1, NULL, &o, &most, &err);
        CHECK(st == RG2_OK && one.rgb && most.rgb && !memcmp(one.rgb, most.rgb, 32 * 32 * 3),
              "threads 1024: %s '%s', or not the bytes of 1 thread", rg2_status_str(st), err.msg);
        rg2_image_free(&one);
        rg2_image_free(&most);
    }
    rg2_render_opts_default(&o);
    o.width = o.height = 32;
    CHECK(rg2_render(&s, 1, NULL, &o, NULL, &err) == RG2_EINVAL && strstr(err.msg, "render: no output image"), "%s",
          err.msg);
    rg2_surface empty = s;
    empty.nu = 0;
    CHECK(rg2_render(&empty, 1, NULL, &o, &a, &err) == RG2_EINVAL && strstr(err.msg, "render: surface 0 has no patches"),
          "%s", err.msg);
    rg2_image none = {0};
    CHECK(rg2_image_write_png(&none, "x.png", &err) == RG2_EINVAL && strstr(err.msg, "png: empty image"), "%s", err.msg);
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &a, &err), &err);
    CHECK(rg2_image_write_png(&a, "", &err) == RG2_EINVAL && strstr(err.msg, "png: no output path"), "%s", err.msg);
    rg2_image_free(&a);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    printf("options: given colour ranges, the Gaussian colour bar, tint, and %zu refused options\n",
           sizeof bad / sizeof bad[0]);
}

/* Default options at w x h pixels, keeping the pixels' surface points (keep_pixels). */
static rg2_render_opts kept_opts(int w, int h)
{
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    o.width = w;
    o.height = h;
    o.keep_pixels = 1;
    return o;
}

/* opts.apart: copies of one sphere band, every other one placed 4 further from the eye, laid out
 * in a grid across the view. Each copy's pixels are exact points of a unit sphere (the centre
 * p - n or p + n is one point to 1e-12); the copies' pixels lie in disjoint boxes of the
 * picture, the centres at one depth, in ceil(sqrt(n)) columns with surface 0 top left; every
 * copy shows about as many pixels (the far ones are brought to the same depth). One surface
 * apart is the picture as placed, byte for byte. */
static void apart(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 6, 4, 0, -M_PI / 3, M_PI / 6, &m, &s, &err), &err);
    rg2_render_opts o = kept_opts(240, 180);
    o.apart = 1;
    double az = o.azimuth * M_PI / 180, el = o.elevation * M_PI / 180;
    double dir[3] = {cos(el) * cos(az), cos(el) * sin(az), sin(el)}, r[3] = {-dir[1], dir[0], 0}, up[3], T[16];
    rg2_surface far;
    CHECK_OK(rg2_surface_copy(&s, &far, &err), &err);
    rg2_xform_translate(T, -4 * dir[0], -4 * dir[1], -4 * dir[2]); /* dir points to the eye */
    rg2_surface_transform(&far, T);
    rg2_surface S[4] = {s, far, s, far};
    rg2_mesh Ms[4] = {m, m, m, m};
    double rn = sqrt(r[0] * r[0] + r[1] * r[1]);
    r[0] /= rn, r[1] /= rn;
    up[0] = -r[1] * dir[2], up[1] = r[0] * dir[2], up[2] = r[1] * dir[0] - r[0] * dir[1]; /* r x f, f = -dir */
    for (int n = 2; n <= 4; n += 2) {
        rg2_image img;
        CHECK_OK(rg2_render(S, n, NULL, &o, &img, &err), &err);
        double c[4][3] = {{0}}, spread = 0;
        int count[4] = {0};
        for (int sgn = -1; sgn <= 1; sgn += 2) { /* the centre candidate p + sgn n that is one point */
            double cc[4][3], sp = 0;
            int seen[4] = {0};
            for (int k = 0; k < img.width * img.height; k++) {
                const rg2_pixel *p = &img.pixels[k];
                if (p->surf < 0)
                    continue;
                for (int q = 0; q < 3; q++) {
                    double x = p->p[q] + sgn * p->n[q];
                    if (!seen[p->surf])
                        cc[p->surf][q] = x;
                    sp = fmax(sp, fabs(x - cc[p->surf][q]));
                }
                seen[p->surf]++;
            }
            if (sgn < 0 || sp < spread) {
                spread = sp;
                memcpy(c, cc, sizeof c);
                memcpy(count, seen, sizeof count);
            }
        }
        int box[4][4]; /* pixel bounding box of each copy: x0, x1, y0, y1 */
        for (int a = 0; a < n; a++)
            box[a][0] = box[a][2] = 1 << 30, box[a][1] = box[a][3] = -1;
        for (int k = 0; k < img.width * img.height; k++) {
            int a = img.pixels[k].surf, px = k % img.width, py = k / img.width;
            if (a < 0)
                continue;
            box[a][0] = px < box[a][0] ? px : box[a][0], box[a][1] = px > box[a][1] ? px : box[a][1];
            box[a][2] = py < box[a][2] ? py : box[a][2], box[a][3] = py > box[a][3] ? py : box[a][3];
        }
        int disjoint = 1;
        for (int a = 0; a < n; a++)
            for (int b = 0; b < a; b++)
                disjoint &= box[a][1] < box[b][0] || box[b][1] < box[a][0] || box[a][3] < box[b][2] ||
                            box[b][3] < box[a][2];
        int lo = count[0], hi = count[0];
        for (int a = 1; a < n; a++)
            lo = count[a] < lo ? count[a] : lo, hi = count[a] > hi ? count[a] : hi;
        double nearest = HUGE_VAL, depth = 0, x[4], y[4];
        for (int a = 0; a < n; a++) {
            x[a] = c[a][0] * r[0] + c[a][1] * r[1] + c[a][2] * r[2];
            y[a] = c[a][0] * up[0] + c[a][1] * up[1] + c[a][2] * up[2];
            for (int b = 0; b < a; b++) {
                double d2 = 0, dd = 0;
                for (int q = 0; q < 3; q++)
                    d2 += (c[a][q] - c[b][q]) * (c[a][q] - c[b][q]), dd += (c[a][q] - c[b][q]) * dir[q];
                nearest = fmin(nearest, sqrt(d2));
                depth = fmax(depth, fabs(dd));
            }
        }
        int layout = n == 2 ? x[0] < x[1] - 2 && fabs(y[0] - y[1]) < 1e-9
                            : x[0] < x[1] - 2 && x[2] < x[3] - 2 && fabs(x[0] - x[2]) < 1e-9 &&
                                  fabs(x[1] - x[3]) < 1e-9 && y[0] > y[2] + 1 && fabs(y[0] - y[1]) < 1e-9 &&
                                  fabs(y[2] - y[3]) < 1e-9;
        printf("apart: %d copies of a sphere band (every other one 4 further): %d..%d pixels each, centre per copy to %.2e, nearest "
               "centres %.3f apart, depth difference %.1e\n",
               n, lo, hi, spread, nearest, depth);
        CHECK(lo > 800 && hi <= lo * 5 / 4, "%d copies show %d..%d pixels each", n, lo, hi);
        CHECK(spread <= 1e-12, "every pixel of a copy lies on its unit sphere: centre to %.3g", spread);
        CHECK(disjoint && depth <= 1e-9, "%d copies: pixel boxes disjoint (%d), depth difference %.3g", n, disjoint,
              depth);
        CHECK(layout, "%d copies in ceil(sqrt(n)) columns, surface 0 top left", n);
        rg2_image_free(&img);
    }
    /* with the mesh overlay, and one surface: as placed */
    o.keep_pixels = 0;
    o.mesh = 1;
    rg2_image a, b;
    CHECK_OK(rg2_render(S, 3, Ms, &o, &a, &err), &err);
    CHECK(a.foreground > 1500, "3 copies with their meshes: %d surface pixels", a.foreground);
    rg2_image_free(&a);
    CHECK_OK(rg2_render(S, 1, Ms, &o, &a, &err), &err);
    o.apart = 0;
    CHECK_OK(rg2_render(S, 1, Ms, &o, &b, &err), &err);
    CHECK(!memcmp(a.rgb, b.rgb, (size_t)o.width * o.height * 3), "one surface apart: the picture as placed");
    rg2_image_free(&a);
    rg2_image_free(&b);
    /* an empty (zeroed) mesh among the meshes has nothing to draw, apart or not: apart, the
     * renderer's copy of it failed, "mesh u: scalars: 0 control points, an open direction needs
     * at least 4", naming neither the render nor the mesh; as placed it was drawn as nothing */
    /* (and one of no rows or no columns, its other count and points kept: as empty) */
    for (int e = 0; e < 3; e++) {
        rg2_mesh Mz[2] = {m, {0}};
        if (e) {
            Mz[1].nu = e == 1 ? 0 : m.nu;
            Mz[1].nv = e == 1 ? m.nv : 0;
            Mz[1].p = m.p;
        }
        for (int ap = 0; ap < 2; ap++) {
            o.apart = ap;
            rg2_status st = rg2_render(S, 2, Mz, &o, &a, &err);
            CHECK(st == RG2_OK && a.foreground > 500,
                  "two surfaces, the second mesh %s, apart %d: %s %s (%d pixels)",
                  e == 0 ? "empty" : e == 1 ? "of no rows" : "of no columns", ap, rg2_status_str(st),
                  st ? err.msg : "", a.foreground);
            rg2_image_free(&a);
        }
    }
    rg2_surface_free(&s);
    rg2_surface_free(&far);
    rg2_mesh_free(&m);
}

/* A surface of more patches than the view fit evaluates at a time (SCENE_CHUNK, 16384) and than
 * the rasteriser takes a chunk (4096): the fit now streams the samples chunk by chunk instead of
 * storing them all (1.2 KB a patch), and the rasteriser's chunks are larger (its 64-patch chunks
 * made thousands of parallel regions). The picture must not depend on the thread count and must
 * fill the view as the fit promises. */
static void many_patches(void)
{
    const char *json = "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}}, \"meshes\": {\"T\": "
                       "{\"shape\": \"t\", \"u\": {\"arcs\": 170}, \"v\": {\"arcs\": 100}}}}";
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_parse(json, strlen(json), "many", &d, &err), &err);
    if (!d)
        return;
    const rg2_surface *s = rg2_design_surface(d, 0);
    CHECK(s->nu * s->nv == 17000, "%d patches", s->nu * s->nv);
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    o.width = 160;
    o.height = 120;
    o.mesh = 1;
    o.mode = RG2_RENDER_MEAN;
    rg2_image one = {0}, two = {0};
    o.threads = 1;
    CHECK_OK(rg2_render(s, 1, rg2_design_mesh(d, 0), &o, &one, &err), &err);
    o.threads = 2;
    CHECK_OK(rg2_render(s, 1, rg2_design_mesh(d, 0), &o, &two, &err), &err);
    size_t nbytes = (size_t)o.width * o.height * 3;
    CHECK(one.rgb && two.rgb && !memcmp(one.rgb, two.rgb, nbytes), "17000 patches: 1 and 2 threads differ");
    /* the torus seen from 25 degrees fills a good part of the fitted view, its pixels resolved
     * on the exact surface (but for a few at the silhouette) */
    CHECK(one.foreground > o.width * o.height / 5 && one.refined >= 0.99 * one.foreground,
          "17000 patches: %d surface pixels, %d refined", one.foreground, one.refined);
    printf("  17000 patches (past one view-fit chunk and many raster chunks): 1 and 2 threads the same bytes, "
           "%d surface pixels\n", one.foreground);
    rg2_image_free(&one);
    rg2_image_free(&two);
    rg2_design_free(d);
}

/* The control-mesh overlay of a mesh with two points far off the view on either side, along
 * the camera's right axis (at `far` from the middle of a 5 x 4 NURBS), from 20 away. */
static int far_overlay(double far, rg2_image *img)
{
    static double pts[5 * 4 * 3];
    static const double U[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8}, V[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 4; j++) {
            double *p = pts + 3 * (i * 4 + j);
            p[0] = i, p[1] = j, p[2] = (i * j) % 3;
        }
    rg2_nurbs nb = {5, 4, pts, NULL, U, V};
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    rg2_status st = rg2_nurbs_mesh(&nb, &m, &err);
    CHECK_OK(st, &err);
    if (st)
        return 1;
    st = rg2_surface_build(&m, &s, &err);
    CHECK_OK(st, &err);
    if (st) {
        rg2_mesh_free(&m);
        return 1;
    }
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    double az = o.azimuth * M_PI / 180.0, r[3] = {-sin(az), cos(az), 0.0}, c[3] = {2.0, 1.5, 1.0};
    double *a = rg2_mesh_at(&m, 0, 0), *b = rg2_mesh_at(&m, 4, 3);
    for (int k = 0; k < 3; k++)
        a[k] = (c[k] - far * r[k]) * a[3], b[k] = (c[k] + far * r[k]) * b[3];
    o.width = 64, o.height = 48, o.mesh = 1, o.distance = 20.0;
    st = rg2_render(&s, 1, &m, &o, img, &err);
    CHECK_OK(st, &err);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    return st != RG2_OK;
}

/* Mesh points far off the view: their projections, past the int range, were converted to int
 * (undefined behaviour; on x86 INT_MIN, and the lines from the mesh's on-screen points to them
 * were not drawn). Now the lines are clipped to the view first: points 1e12 away give the
 * picture of points 1e8 away (whose projections, 4.5e8 pixels off, fit an int). */
static void far_mesh_points(void)
{
    rg2_image near = {0}, far = {0};
    if (!far_overlay(1e8, &near) && !far_overlay(1e12, &far)) {
        int differ = 0, edge = 0;
        for (int k = 0; k < 64 * 48 * 3; k++)
            differ += abs(near.rgb[k] - far.rgb[k]) > 8;
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 64; x += 63) {
                const unsigned char *p = far.rgb + 3 * (y * 64 + x);
                edge += p[0] > 2 * p[1] && p[0] > 2 * p[2]; /* the overlay's red */
            }
        CHECK(differ == 0, "mesh points 1e12 off the view: %d bytes differ from points 1e8 off", differ);
        CHECK(edge >= 2, "mesh points 1e12 off the view: %d red pixels at the left and right edges", edge);
    }
    rg2_image_free(&near);
    rg2_image_free(&far);
}

/* The robust colour range clips the fraction p at each end (rg2_render_opts.percentile): counted
 * over the surface pixels' own H (mean) or |K| (Gauss, symmetric about 0), at most p (m - 1) of
 * the m values lie beyond each end and more than that reach it (the end is a pixel's value). */
static void robust_range(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    /* at any scale: the torus times 1e5 (|K| <= 1.1e-11) had its K range floored at +-5e-10, one
     * flat grey; times 1e-4 */
    const double scale[3] = {1.0, 1e5, 1e-4 / 1e5};
    for (int q = 0; q < 12; q++) {
        if (q % 4 == 0 && q) {
            double M[16] = {scale[q / 4], 0, 0, 0, 0, scale[q / 4], 0, 0, 0, 0, scale[q / 4], 0, 0, 0, 0, 1};
            rg2_surface_transform(&s, M);
        }
        rg2_render_opts o = kept_opts(160, 120);
        o.mode = q % 4 < 2 ? RG2_RENDER_MEAN : RG2_RENDER_GAUSS;
        o.percentile = q % 2 ? 0.1 : 0.02;
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        int gauss = o.mode == RG2_RENDER_GAUSS, n = 0, below = 0, to_lo = 0, above = 0, to_hi = 0;
        for (int k = 0; img.pixels && k < img.width * img.height; k++) {
            const rg2_pixel *p = &img.pixels[k];
            if (p->surf < 0)
                continue;
            double v = gauss ? fabs(p->K) : p->H;
            n++;
            below += !gauss && v < img.range[0], to_lo += !gauss && v <= img.range[0];
            above += v > img.range[1], to_hi += v >= img.range[1];
        }
        double clip = o.percentile * (n - 1);
        int lo_ok = gauss ? img.range[0] == -img.range[1] : below <= clip && to_lo > clip;
        CHECK(n > 2000 && lo_ok && above <= clip && to_hi > clip,
              "%s, percentile %g, torus times %g: range [%g, %g] of %d pixels: %d / %d below / at most lo, %d / %d "
              "above / at least hi, want <= %g < 'at most' / 'at least'",
              gauss ? "|K|" : "H", o.percentile, q < 4 ? 1.0 : q < 8 ? 1e5 : 1e-4, img.range[0], img.range[1], n,
              below, to_lo, above, to_hi, clip);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Whether pixel k of img has a background pixel among its in-image 4-neighbours (a silhouette
 * pixel, which the outline darkens). */
static int at_silhouette(const rg2_image *img, int k)
{
    int W = img->width, x = k % W, y = k / W;
    return (x > 0 && img->pixels[k - 1].surf < 0) || (x + 1 < W && img->pixels[k + 1].surf < 0) ||
           (y > 0 && img->pixels[k - W].surf < 0) || (y + 1 < img->height && img->pixels[k + W].surf < 0);
}

/* Zebra stripes are anti-aliased by the signed distance sin(N phase) / D to the stripe edge, D the
 * largest change of sin(N phase) to an in-image 4-neighbour on the surface: the pixel's grey is
 * (0.06 + 0.90 c) times a diffuse factor in [0.8, 1], c = clamp(0.5 + sin(N phase) / D). Computed
 * here from each pixel's exact phase, on a torus seen from close by (the surface runs off the
 * picture at its edges, where the neighbours outside do not count). */
static void zebra_antialias(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    rg2_render_opts o = kept_opts(120, 90);
    o.mode = RG2_RENDER_ZEBRA;
    o.distance = 5;
    rg2_image img;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
    int W = img.width, H = img.height, checked = 0, edge = 0, border = 0, off = 0, worst_k = -1;
    double N = o.stripes;
    for (int k = 0; img.pixels && k < W * H; k++) {
        const rg2_pixel *p = &img.pixels[k];
        if (p->surf < 0 || at_silhouette(&img, k))
            continue;
        int x = k % W, y = k / W;
        double sv = sin(N * p->phase), D = 0;
        const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        for (int q = 0; q < 4; q++) {
            int X = x + nb[q][0], Y = y + nb[q][1];
            if (X >= 0 && Y >= 0 && X < W && Y < H && img.pixels[Y * W + X].surf >= 0)
                D = fmax(D, fabs(sin(N * img.pixels[Y * W + X].phase) - sv));
        }
        double c = D > 0 ? fmin(1, fmax(0, 0.5 + sv / D)) : sv > 0, grey = 0.06 + 0.90 * c;
        const unsigned char *b = img.rgb + 3 * (size_t)k;
        int ok = b[0] == b[1] && b[1] == b[2] && b[0] >= floor(255 * 0.8 * grey) - 1 && b[0] <= ceil(255 * grey) + 1;
        if (!ok && worst_k < 0)
            worst_k = k;
        off += !ok;
        checked++;
        edge += c > 0.1 && c < 0.9;
        border += x == 0 || y == 0 || x == W - 1 || y == H - 1;
    }
    CHECK(checked > W * H / 2 && edge > 100 && border > 50 && off == 0,
          "zebra anti-aliasing: %d of %d surface pixels (%d on a stripe edge, %d at the picture's edge) off their "
          "coverage's grey, the first at pixel %d",
          off, checked, edge, border, worst_k);
    printf("zebra anti-aliasing: %d surface pixels (%d on stripe edges, %d at the picture's edge) grey as their "
           "exact phases' coverage\n", checked, edge, border);
    rg2_image_free(&img);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Shaded: a lit surface, not a flat one. The untinted sphere band shades from dark on the side away
 * from the lights to bright: the darkest pixel (off the silhouette) is at most half the brightest. */
static void shaded_contrast(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 6, 4, 0, -M_PI / 3, M_PI / 6, &m, &s, &err), &err);
    rg2_render_opts o = kept_opts(120, 90);
    rg2_image img;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
    int lo = 255, hi = 0, fg = 0;
    for (int k = 0; img.pixels && k < img.width * img.height; k++) {
        if (img.pixels[k].surf < 0 || at_silhouette(&img, k))
            continue;
        int g = img.rgb[3 * (size_t)k + 1];
        lo = g < lo ? g : lo, hi = g > hi ? g : hi;
        fg++;
    }
    CHECK(fg > 1000 && 2 * lo <= hi, "shaded sphere band: %d pixels, green %d..%d: not lit", fg, lo, hi);
    printf("shaded sphere band: %d pixels, green levels %d..%d\n", fg, lo, hi);
    rg2_image_free(&img);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Pixels Newton cannot bring onto their ray (at the silhouette, where the ray grazes the patch or
 * passes it) keep the best point it found, from the z-buffer's perspective-correct (u, v) on: still
 * within a tenth of a pixel of the ray. Torus (radius 4 about the origin) from 20 away: a pixel at
 * depth <= 28 spans 28 * 2 tan(fov / 2) / 120 of the scene. (All pixels count: whether a few at the
 * silhouette stay off their ray depends on rounding.) */
static void silhouette_pixels(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    for (int q = 0; q < 2; q++) {
        rg2_render_opts o = kept_opts(160, 120);
        o.distance = 20;
        o.azimuth = q ? 115 : 35;
        o.elevation = q ? -35 : 25;
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        double pixel = 28 * 2 * tan(o.fov / 2 * M_PI / 180) / o.height, worst = 0;
        for (int k = 0; img.pixels && k < o.width * o.height; k++)
            if (img.pixels[k].surf >= 0)
                worst = fmax(worst, img.pixels[k].resid);
        CHECK(img.foreground > 2000 && worst <= 0.1 * pixel,
              "view %d: %d pixels, %d on their ray; the worst %.3g of a pixel from it", q, img.foreground, img.refined,
              worst / pixel);
        printf("torus from 20 away, view %d: %d of %d pixels on their ray (Newton), the others within %.3f of a pixel\n",
               q, img.refined, img.foreground, worst / pixel);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* A pixel whose ray meets a pole: Newton ends on the collapsed side, where rg2_surface_eval has
 * no normal (n = 0, K = H = 0). The renderer takes the limit there (rg2_surface_eval_limit): the
 * whole sphere seen from straight above its pole (97 x 97, the pole on the centre pixel's ray)
 * has a unit normal and K = 1 at every pixel, and the shaded pole pixel is lit like its
 * neighbours (it was shaded as facing away from the lights: a dark speck). */
static void pole_pixels(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 4, 4, 1, 0, 0, &m, &s, &err), &err);
    for (int q = 0; q < 2; q++) {
        rg2_render_opts o = kept_opts(97, 97);
        o.elevation = q ? -90 : 90;
        o.azimuth = 20;
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        int W = img.width, H = img.height, fg = 0, nonunit = 0, offK = 0, specks = 0, first = -1;
        double worstK = 0;
        for (int k = 0; img.pixels && k < W * H; k++) {
            const rg2_pixel *p = &img.pixels[k];
            if (p->surf < 0)
                continue;
            fg++;
            double nn = sqrt(p->n[0] * p->n[0] + p->n[1] * p->n[1] + p->n[2] * p->n[2]);
            nonunit += !(fabs(nn - 1) <= 1e-12);
            offK += !(fabs(p->K - 1) <= 1e-6);
            worstK = fmax(worstK, fabs(p->K - 1));
            int x = k % W, y = k / W;
            if (x == 0 || y == 0 || x == W - 1 || y == H - 1 || at_silhouette(&img, k))
                continue;
            /* shaded: a pixel darker than 0.8 x the darkest of its 4-neighbours is a speck */
            int g = img.rgb[3 * (size_t)k + 1], lo = 255;
            const int nb[4] = {1, -1, W, -W};
            for (int e = 0; e < 4; e++)
                lo = img.rgb[3 * (size_t)(k + nb[e]) + 1] < lo ? img.rgb[3 * (size_t)(k + nb[e]) + 1] : lo;
            if (g < 0.8 * lo) {
                specks++;
                if (first < 0)
                    first = k;
            }
        }
        printf("sphere from straight %s its pole: %d pixels, %d without a unit normal, %d with |K - 1| > 1e-6 "
               "(worst %.2e), %d dark specks\n",
               q ? "below" : "above", fg, nonunit, offK, worstK, specks);
        CHECK(fg > 3000 && nonunit == 0 && offK == 0 && specks == 0,
              "elevation %g: %d pixels, %d without a unit normal, %d with |K - 1| > 1e-6 (worst %.3g), %d dark "
              "specks (the first at pixel (%d, %d))",
              o.elevation, fg, nonunit, offK, worstK, specks, first % W, first / W);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Views straight down or up (elevation +-90) continue those next to them: at elevation 90 the
 * picture of Fig. 8's torus and sphere is that at 89.9999 (the same azimuth), and the azimuth
 * still turns it. (The right vector was +x or -x at +-90 whatever the azimuth: the view turned
 * by 90 - A degrees between 89.9999 and 90.) */
static int pictures_differ(const rg2_image *a, const rg2_image *b)
{
    int n = 0;
    for (size_t k = 0; a->rgb && b->rgb && k < (size_t)a->width * a->height; k++)
        for (int c = 0; c < 3; c++)
            if (abs(a->rgb[3 * k + c] - b->rgb[3 * k + c]) > 24) {
                n++;
                break;
            }
    return n;
}

static void polar_views(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/torus_sphere.json", &d, &err), &err);
    if (!d)
        return;
    const rg2_surface *s = rg2_design_surface(d, 0);
    for (int q = 0; q < 2; q++) {
        double el = q ? -90 : 90;
        rg2_render_opts o = kept_opts(160, 120);
        o.keep_pixels = 0;
        o.azimuth = 35;
        rg2_image at, near, turned;
        o.elevation = el;
        CHECK_OK(rg2_render(s, 1, NULL, &o, &at, &err), &err);
        o.elevation = el * (1 - 1e-6);
        CHECK_OK(rg2_render(s, 1, NULL, &o, &near, &err), &err);
        o.elevation = el;
        o.azimuth = 125;
        CHECK_OK(rg2_render(s, 1, NULL, &o, &turned, &err), &err);
        int n_near = pictures_differ(&at, &near), n_turned = pictures_differ(&at, &turned);
        printf("elevation %g: %d of %d pixels differ from elevation %g, %d from azimuth 125\n", el, n_near,
               at.width * at.height, o.elevation * (1 - 1e-6), n_turned);
        CHECK(n_near <= at.width * at.height / 200 && n_turned >= at.width * at.height / 20,
              "elevation %g, azimuth 35: %d pixels differ from elevation %g, %d from azimuth 125", el, n_near,
              el * (1 - 1e-6), n_turned);
        rg2_image_free(&at);
        rg2_image_free(&near);
        rg2_image_free(&turned);
    }
    rg2_design_free(d);
}

/* The colour bar's five labels read differently: a sphere band's constant H gets the narrowest
 * range, -1 +- 5e-4, which three significant digits labelled -1 at four of its five ticks. Each
 * label's ink (right of the bar, rows y - 3 .. y + 3 of its tick) is compared. */
static void colour_bar_labels(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 6, 4, 0, -M_PI / 3, M_PI / 6, &m, &s, &err), &err);
    for (int q = 0; q < 2; q++) {
        rg2_render_opts o = kept_opts(400, 300);
        o.mode = RG2_RENDER_MEAN;
        if (q) { /* a wide range: the labels as before, 3 digits */
            o.range_set = 1;
            o.range[0] = -2;
            o.range[1] = 1;
        }
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        int W = img.width, x0 = W - 110 + 12 + 22 + 7, top = 40, bot = img.height - 40, same = 0, inked = 0;
        for (int a = 0; a < 5 && img.rgb; a++) {
            int ya = bot - (bot - top) * a / 4, ink = 0;
            for (int y = ya - 3; y <= ya + 3; y++)
                for (int x = x0; x < W; x++)
                    ink += img.rgb[3 * ((size_t)y * W + x)] < 128;
            inked += ink > 0;
            for (int b = 0; b < a; b++) {
                int yb = bot - (bot - top) * b / 4, differ = 0; /* the ink (the background is a gradient) */
                for (int dy = -3; dy <= 3; dy++)
                    for (int x = x0; x < W; x++)
                        differ |= (img.rgb[3 * ((size_t)(ya + dy) * W + x)] < 128) !=
                                  (img.rgb[3 * ((size_t)(yb + dy) * W + x)] < 128);
                same += !differ;
            }
        }
        printf("colour bar, H range [%.6g, %.6g]: %d labels drawn, %d pairs of them alike\n", img.range[0],
               img.range[1], inked, same);
        CHECK(inked == 5 && same == 0, "range [%.9g, %.9g]: %d labels drawn, %d pairs read the same", img.range[0],
              img.range[1], inked, same);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Pixels whose H or K lies beyond the colour range are drawn in the end colour; the bar marks
 * each end that has any with a triangle past it (rg2_image.below / above). A torus's mean map at
 * the robust range (2 % clipped at each end) has both, its Gauss map (K from -1/2 to 1/4, the
 * range symmetric about 0) only the bottom one; with the range [-100, -99] (every H above
 * it) only the top one; with [-2, 1] (every H inside) none, and the rows past the bar are the
 * background there (each pixel equal to the one 6 columns left of the bar, the background's
 * gradient being vertical). The counts agree with the kept pixels' H. */
static void bar_arrows(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    static const struct {
        int set, mode;
        double lo, hi;
        int below, above; /* want: 1 some, 0 none, -1 all of the foreground */
    } cases[] = {{0, RG2_RENDER_MEAN, 0, 0, 1, 1},
                 {0, RG2_RENDER_GAUSS, 0, 0, 1, 0}, /* K in [-1/2, 1/4]: the range +-0.497, symmetric */
                 {1, RG2_RENDER_MEAN, -100, -99, 0, -1},
                 {1, RG2_RENDER_MEAN, 10, 11, -1, 0},
                 {1, RG2_RENDER_MEAN, -2, 1, 0, 0}};
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        rg2_render_opts o = kept_opts(400, 300);
        o.mode = cases[c].mode;
        o.range_set = cases[c].set;
        o.range[0] = cases[c].lo;
        o.range[1] = cases[c].hi;
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        if (!img.rgb || !img.pixels)
            continue;
        int W = img.width, x0 = W - 110 + 12, bw = 22, top = 40, bot = img.height - 40, below = 0, above = 0;
        for (int k = 0; k < W * img.height; k++)
            if (img.pixels[k].surf >= 0) {
                double v = o.mode == RG2_RENDER_GAUSS ? img.pixels[k].K : img.pixels[k].H;
                below += v < img.range[0];
                above += v > img.range[1];
            }
        /* pixels past each end of the bar, over its columns, unlike the background beside them */
        int marked[2] = {0, 0}, asym = 0, rows_off = 0;
        for (int e = 0; e < 2; e++)
            for (int r = 2; r <= 12; r++) {
                int y = e ? bot + r : top - r, in_row = 0;
                const unsigned char *bg = img.rgb + 3 * ((size_t)y * W + x0 - 6);
                for (int x = x0; x < x0 + bw; x++) {
                    int mk = memcmp(img.rgb + 3 * ((size_t)y * W + x), bg, 3) != 0;
                    int mirror = memcmp(img.rgb + 3 * ((size_t)y * W + (2 * x0 + bw - 1 - x)), bg, 3) != 0;
                    marked[e] += mk, in_row += mk, asym += mk != mirror;
                }
                /* the triangle's row r - 2 from its base: |x - centre| <= 21/2 (12 - r) / 10 + 1/2,
                 * 2 (floor(1.05 (12 - r)) + 1) pixels (22, 20, 18, ..., 4, 2) where it is drawn */
                int want_row = 2 * ((int)floor(1.05 * (12 - r)) + 1);
                rows_off += (e ? img.below : img.above) > 0 && in_row != want_row;
            }
        /* inside its dark rim (rows 1..9 from its base, |x - centre| <= half - 1, half = 10.5 (10 - r) / 10), each
         * triangle is the end colour: the colour of the bar's end row; its rim is the ink of the labels (the H's
         * top left pixel, 28 rows above the bar) and of the ticks (the top one right of the bar) */
        const unsigned char *letter = img.rgb + 3 * ((size_t)(top - 28) * W + x0);
        int fill_off = 0, ink_off = memcmp(img.rgb + 3 * ((size_t)top * W + x0 + bw), letter, 3) != 0;
        for (int e = 0; e < 2; e++) {
            if (!(e ? img.below : img.above))
                continue;
            const unsigned char *end = img.rgb + 3 * ((size_t)(e ? bot : top) * W + x0);
            for (int r = 0; r <= 10; r++) {
                int y = e ? bot + 2 + r : top - 2 - r, inside = 0, coloured = 0;
                const unsigned char *bg = img.rgb + 3 * ((size_t)y * W + x0 - 6);
                for (int x = x0; x < x0 + bw; x++) {
                    const unsigned char *px = img.rgb + 3 * ((size_t)y * W + x);
                    inside += r > 0 && r < 10 && fabs(x - (x0 + 10.5)) <= 10.5 * (10 - r) / 10.0 - 1.0;
                    coloured += !memcmp(px, end, 3);
                    ink_off += memcmp(px, end, 3) && memcmp(px, bg, 3) && memcmp(px, letter, 3);
                }
                fill_off += inside != coloured;
            }
        }
        CHECK(!fill_off && !ink_off, "case %zu: %d rows of a triangle whose pixels in the end colour are not its "
              "inside; %d pixels of its rim or the ticks not in the labels' ink", c, fill_off, ink_off);
        printf("%s map, range [%.4g, %.4g]: %d pixels below, %d above (of %d); %d and %d pixels marked past the bar's "
               "bottom and top\n",
               o.mode == RG2_RENDER_GAUSS ? "Gauss" : "mean", img.range[0], img.range[1], img.below, img.above,
               img.foreground, marked[1], marked[0]);
        CHECK(img.below == below && img.above == above, "case %zu: below %d, above %d; the pixels say %d and %d", c,
              img.below, img.above, below, above);
        int want[2] = {cases[c].below, cases[c].above}, got[2] = {img.below, img.above};
        for (int e = 0; e < 2; e++) {
            int ok = want[e] < 0 ? got[e] == img.foreground : want[e] ? got[e] > 0 && got[e] < img.foreground : !got[e];
            CHECK(ok, "case %zu: %d pixels %s the range (of %d)", c, got[e], e ? "above" : "below", img.foreground);
            /* a triangle of 11 rows over the 22 columns: about 120 pixels */
            int mk = marked[e ? 0 : 1];
            CHECK(want[e] ? mk == 132 : mk == 0, "case %zu: %d pixels marked past the bar's %s (want %d)", c, mk,
                  e ? "top" : "bottom", want[e] ? 132 : 0);
        }
        /* each triangle is symmetric about the bar's middle, 10.5 columns from its first, and
         * each of its rows is as wide as drawn by hand */
        CHECK(!asym && !rows_off, "case %zu: %d pixels past the bar's ends whose mirror image about the bar's middle "
              "differs, %d rows of a triangle of another width", c, asym, rows_off);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* A curvature picture too low for the colour bar (under 120 rows) uses the whole width: it kept
 * the bar's 110 columns on the right empty. The sphere band at 400 x 100 is centred. */
static void low_picture_bar(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 6, 4, 0, -M_PI / 3, M_PI / 6, &m, &s, &err), &err);
    rg2_render_opts o = kept_opts(400, 100);
    o.mode = RG2_RENDER_GAUSS;
    rg2_image img;
    CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
    int lo = img.width, hi = -1;
    for (int k = 0; img.pixels && k < img.width * img.height; k++)
        if (img.pixels[k].surf >= 0) {
            int x = k % img.width;
            lo = x < lo ? x : lo, hi = x > hi ? x : hi;
        }
    printf("Gauss map at 400 x 100 (no room for the colour bar): surface pixels in columns %d..%d\n", lo, hi);
    CHECK(hi >= 0 && abs((lo + hi + 1) - img.width) <= 4, "400 x 100: the surface spans columns %d..%d, not centred",
          lo, hi);
    rg2_image_free(&img);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The control mesh stays in the view, left of the colour bar: zoomed in on the torus (its mesh
 * runs off the view), the bar's 110 columns of the mean map are the same with --mesh as
 * without (mesh lines were drawn across the bar and its labels). */
static void mesh_off_bar(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    rg2_render_opts o = kept_opts(400, 300);
    o.keep_pixels = 0;
    o.mode = RG2_RENDER_MEAN;
    o.distance = 6;
    rg2_image plain, meshed;
    CHECK_OK(rg2_render(&s, 1, &m, &o, &plain, &err), &err);
    o.mesh = 1;
    CHECK_OK(rg2_render(&s, 1, &m, &o, &meshed, &err), &err);
    int W = plain.width, bar = 0, view = 0;
    for (int k = 0; plain.rgb && meshed.rgb && k < W * plain.height; k++) {
        int differ = memcmp(plain.rgb + 3 * (size_t)k, meshed.rgb + 3 * (size_t)k, 3) != 0;
        if (k % W >= W - 110)
            bar += differ;
        else
            view += differ;
    }
    printf("mesh over a zoomed mean map: %d pixels of the view and %d of the colour bar's columns changed\n", view,
           bar);
    CHECK(view > 1000 && bar == 0, "--mesh changed %d pixels of the view and %d in the colour bar's columns", view, bar);
    rg2_image_free(&plain);
    rg2_image_free(&meshed);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Whether patches a and b of s touch (share an edge or a corner, across closures too). */
static int patches_touch(const rg2_surface *s, int a, int b)
{
    int di = abs(a / s->nv - b / s->nv), dj = abs(a % s->nv - b % s->nv);
    if (di == s->nu - 1)
        di = 1;
    if (dj == s->nv - 1)
        dj = 1;
    return di <= 1 && dj <= 1;
}

/* Patch boundaries at any picture size: a surface pixel (off the silhouette) with a 4-neighbour
 * on a touching patch lies at a seam, and --boundaries darkens at least 90% of them in small
 * pictures too. The limit on the neighbours' distance was 2% of the scene alone, less than a
 * pixel's footprint there: at 64x48, 11% of torus_sphere's seam pixels and none of pipe_elbow's
 * were drawn, at 120x90 77% and 72%. */
static void small_boundaries(void)
{
    static const char *const files[2] = {"examples/torus_sphere.json", "examples/pipe_elbow.json"};
    static const int sizes[2][2] = {{64, 48}, {120, 90}};
    for (int f = 0; f < 2; f++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(files[f], &d, &err), &err);
        if (!d)
            continue;
        const rg2_surface *s = rg2_design_surface(d, 0);
        for (int q = 0; q < 2; q++) {
            rg2_render_opts o = kept_opts(sizes[q][0], sizes[q][1]);
            rg2_image plain, lines;
            CHECK_OK(rg2_render(s, 1, NULL, &o, &plain, &err), &err);
            o.boundaries = 1;
            o.keep_pixels = 0;
            CHECK_OK(rg2_render(s, 1, NULL, &o, &lines, &err), &err);
            int W = plain.width, H = plain.height, seam = 0, drawn = 0, elsewhere = 0;
            for (int y = 1; plain.pixels && lines.rgb && y < H - 1; y++)
                for (int x = 1; x < W - 1; x++) {
                    int k = y * W + x, at = 0;
                    const rg2_pixel *p = &plain.pixels[k];
                    const int nb[4] = {k - 1, k + 1, k - W, k + W};
                    if (p->surf < 0 || at_silhouette(&plain, k))
                        continue;
                    for (int e = 0; e < 4; e++)
                        at |= plain.pixels[nb[e]].patch != p->patch && patches_touch(s, p->patch, plain.pixels[nb[e]].patch);
                    int dark = memcmp(plain.rgb + 3 * (size_t)k, lines.rgb + 3 * (size_t)k, 3) != 0;
                    seam += at, drawn += at && dark, elsewhere += !at && dark;
                }
            printf("%s %dx%d: %d of %d seam pixels drawn as patch boundary, %d other pixels\n", files[f] + 9, W, H,
                   drawn, seam, elsewhere);
            CHECK(seam > 100 && drawn >= seam * 9 / 10 && elsewhere == 0,
                  "%s at %dx%d: %d of %d seam pixels drawn as boundary, %d other pixels", files[f], W, H, drawn, seam,
                  elsewhere);
            rg2_image_free(&plain);
            rg2_image_free(&lines);
        }
        rg2_design_free(d);
    }
}

/* --stripes N counts stripe pairs per full turn of the reflected ray about the light-line axis:
 * over the pixels of a sphere band, whose reflected rays turn all the way round, the stripe
 * colour (from the picture) taken in the order of the pixels' phases changes 2N times. */
static void stripes_per_turn(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(0.0, 1.0, 6, 4, 0, -M_PI / 3, M_PI / 6, &m, &s, &err), &err);
    for (int N = 3; N <= 7; N += 4) {
        rg2_render_opts o = kept_opts(240, 180);
        o.mode = RG2_RENDER_ZEBRA;
        o.stripes = N;
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        enum { BINS = 720 };
        int white[BINS] = {0}, black[BINS] = {0};
        for (int k = 0; img.pixels && k < img.width * img.height; k++) {
            if (img.pixels[k].surf < 0)
                continue;
            int b = (int)floor((img.pixels[k].phase + M_PI) / (2 * M_PI) * BINS);
            b = b < 0 ? 0 : (b >= BINS ? BINS - 1 : b);
            if (img.rgb[3 * (size_t)k] > 160)
                white[b]++;
            else if (img.rgb[3 * (size_t)k] < 60)
                black[b]++;
        }
        int changes = 0, first = -1, last = -1, filled = 0;
        for (int b = 0; b < BINS; b++) {
            if (white[b] + black[b] == 0)
                continue;
            int c = white[b] > black[b];
            filled++;
            if (first < 0)
                first = c;
            else
                changes += c != last;
            last = c;
        }
        changes += first >= 0 && last != first; /* round the turn */
        printf("zebra, %d stripe pairs: %d of %d phase bins seen, the colour changes %d times in a turn\n", N, filled,
               BINS, changes);
        CHECK(filled > BINS * 9 / 10 && changes == 2 * N, "--stripes %d: %d colour changes in a turn of the phase (%d "
              "of %d bins seen), want %d", N, changes, filled, BINS, 2 * N);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* A flat surface: the open G2 surface of an 8 x 7 control mesh in the plane z = 0, its points
 * (i, j) moved off the grid by up to 0.3. Every derivative lies in the plane: H = K = 0. */
static rg2_status flat_mesh(rg2_mesh *m, rg2_surface *s, rg2_error *err)
{
    memset(s, 0, sizeof *s);
    rg2_status st = rg2_mesh_init(m, 8, 7, 0, 0, err);
    if (st)
        return st;
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 7; j++) {
            double *p = rg2_mesh_at(m, i, j);
            p[0] = i + 0.3 * sin(3.0 * i + 5.0 * j), p[1] = j + 0.3 * cos(2.0 * i - 7.0 * j), p[2] = 0, p[3] = 1;
        }
    return rg2_surface_build(m, s, err);
}

/* Distance from q to the segment a-b in the plane z = 0. */
static double seg_dist2d(const double *q, const double *a, const double *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return hypot(q[0] - a[0] - t * dx, q[1] - a[1] - t * dy);
}

/* The control-mesh overlay where the mesh is: seen straight down, the flat surface and its
 * mesh (both in z = 0) are drawn to scale (a plane across the view projects by a similarity),
 * so a surface pixel's exact point p, over the pixel width f measured on the picture, gives its
 * distance in pixels to each leg (i, j)-(i + 1, j), (i, j)-(i, j + 1) and each point. The
 * overlay is anti-aliased lines of half-width 0.6 and dots of half-width 2.2 (coverage
 * hw + 0.5 - distance): a pixel it reddens lies within 1.1 of a leg or 2.7 of a point, and
 * every pixel within 0.3 of a leg or 1.5 of a point is red. (The untinted surface is grey with
 * R <= G: red R > G + 2 is the overlay's, at a coverage of 2% or more.) */
static void mesh_legs(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(flat_mesh(&m, &s, &err), &err);
    rg2_render_opts o = kept_opts(240, 200);
    o.elevation = 90;
    o.mesh = 1;
    rg2_image img;
    CHECK_OK(rg2_render(&s, 1, &m, &o, &img, &err), &err);
    int W = 240, H = 200, y = H / 2, a = -1, b = -1, stray = 0, faint = 0, near = 0, reddened = 0;
    for (int x = 0; img.pixels && x < W; x++)
        if (img.pixels[y * W + x].surf >= 0)
            b = x, a = a < 0 ? x : a;
    double f = 0;
    if (a >= 0 && b > a) {
        const double *pa = img.pixels[y * W + a].p, *pb = img.pixels[y * W + b].p;
        f = hypot(pb[0] - pa[0], pb[1] - pa[1]) / (b - a);
    }
    for (int k = 0; f > 0 && img.rgb && k < W * H; k++) {
        const rg2_pixel *p = &img.pixels[k];
        if (p->surf < 0)
            continue;
        double dl = HUGE_VAL, dp = HUGE_VAL;
        for (int i = 0; i < m.nu; i++)
            for (int j = 0; j < m.nv; j++) {
                const double *c = rg2_mesh_at(&m, i, j);
                dp = fmin(dp, hypot(p->p[0] - c[0], p->p[1] - c[1]) / f);
                if (i + 1 < m.nu)
                    dl = fmin(dl, seg_dist2d(p->p, c, rg2_mesh_at(&m, i + 1, j)) / f);
                if (j + 1 < m.nv)
                    dl = fmin(dl, seg_dist2d(p->p, c, rg2_mesh_at(&m, i, j + 1)) / f);
            }
        const unsigned char *q = img.rgb + 3 * (size_t)k;
        int tinged = q[0] > q[1] + 2, red = q[0] >= q[1] + 80 && q[0] >= q[2] + 80;
        reddened += tinged;
        stray += tinged && !(dl < 1.1 || dp < 2.7);
        if (dl <= 0.3 || dp <= 1.5)
            near++, faint += !red;
    }
    printf("mesh over a flat surface seen straight down (%.4g per pixel): %d pixels reddened, %d off the legs and "
           "points; %d of %d pixels on them not red\n", f, reddened, stray, faint, near);
    CHECK(f > 0 && near > 300 && !stray && !faint, "mesh overlay: %d reddened pixels off the legs and points, %d of %d "
          "pixels on them not red (pixel width %g)", stray, faint, near, f);
    rg2_image_free(&img);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The floor of the robust colour range is 1e-9 / rho for H and 1e-9 / rho^2 for K, rho the
 * radius of the scene's bounding sphere (docs/render.md, --range): a flat surface (H = K = 0)
 * sits mid-bar in a range exactly that wide. Seen straight down at azimuth 0, the view's right
 * and up vectors are +y and -x, and the samples (7 x 7 a patch, u and v at k / 6) have no depth
 * extent: rho is half the diagonal of their box in x and y. At sizes 1 and 1e-3. */
static void flat_range(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(flat_mesh(&m, &s, &err), &err);
    for (int q = 0; q < 4; q++) {
        if (q == 2) {
            double M[16] = {1e-3, 0, 0, 0, 0, 1e-3, 0, 0, 0, 0, 1e-3, 0, 0, 0, 0, 1};
            rg2_surface_transform(&s, M);
        }
        double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < s.nv; j++)
                for (int a = 0; a <= 6; a++)
                    for (int b = 0; b <= 6; b++) {
                        rg2_eval e;
                        rg2_surface_eval(&s, i, j, a / 6.0, b / 6.0, 0, &e);
                        for (int k = 0; k < 2; k++)
                            lo[k] = fmin(lo[k], e.p[k]), hi[k] = fmax(hi[k], e.p[k]);
                    }
        double rho = 0.5 * hypot(hi[0] - lo[0], hi[1] - lo[1]);
        rg2_render_opts o = kept_opts(240, 160);
        o.elevation = 90;
        o.azimuth = 0;
        o.mode = q % 2 ? RG2_RENDER_GAUSS : RG2_RENDER_MEAN;
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        double want = q % 2 ? 1e-9 / (rho * rho) : 1e-9 / rho, got = img.range[1] - img.range[0];
        printf("flat %s map at size %g: range [%.6g, %.6g], %.9g of 1e-9 / rho%s (rho %.6g)\n", q % 2 ? "K" : "H",
               q < 2 ? 1.0 : 1e-3, img.range[0], img.range[1], got / want, q % 2 ? "^2" : "", rho);
        CHECK(img.foreground > 5000 && fabs(got / want - 1) < 1e-9 && img.range[0] == -img.range[1],
              "flat %s map: range [%g, %g], want +-%g", q % 2 ? "K" : "H", img.range[0], img.range[1], 0.5 * want);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* A patch whose points overflow in x alone (homogeneous x 1e308 at weight 0.5: x = 2e308, y and
 * z finite) is refused as the tessellation refuses it: outside the numeric range (control points
 * up to 1e60), RG2_EDOMAIN naming the surface, the picture left empty; so is one at x = 2e60, just
 * past the range, while one at 0.5e60 is drawn. A patch whose 4-tuples are all 0 (every point at
 * infinity, with no coordinates) has no finite sample and is left out of the view. */
static void overflowing_patch(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    const double hx[4] = {1e308, 1e60, 0.25e60, 0.0};
    for (int q = 0; q < 4; q++) {
        for (int r = 0; r < 4; r++)
            for (int t = 0; t < 4; t++) {
                double *h = s.patch[9].h[r][t];
                if (q < 3)
                    h[0] = hx[q], h[1] = 0.5 * h[1] / h[3], h[2] = 0.5 * h[2] / h[3], h[3] = 0.5;
                else
                    h[0] = h[1] = h[2] = h[3] = 0;
            }
        rg2_render_opts o = kept_opts(96, 72);
        rg2_image img;
        memset(&img, 0xff, sizeof img);
        rg2_status st = rg2_render(&s, 1, NULL, &o, &img, &err);
        if (q < 2) {
            CHECK(st == RG2_EDOMAIN && strstr(err.msg, "render: surface 0") && strstr(err.msg, "1e+60") && !img.rgb &&
                      img.width == 0,
                  "a patch at x = %g: status %d (%s), the picture %s", 2 * hx[q], (int)st, err.msg,
                  img.rgb ? "written" : "left empty");
            printf("a patch at x = %g: %s\n", 2 * hx[q], err.msg);
        } else {
            CHECK(st == RG2_OK && (q == 2 || img.foreground > 1000),
                  "a patch at x = %g: status %d (%s), %d foreground pixels", 2 * hx[q], (int)st, err.msg,
                  img.foreground);
            if (st == RG2_OK)
                rg2_image_free(&img);
        }
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The curvature maps' colours follow each pixel's own value (docs/render.md): the mean map runs
 * violet, blue, green, yellow, red from the low end of the range, the Gauss map is blue below 0
 * and red above, "red where K > 0.2 of the range, blue where K < -0.2 of it". On the torus,
 * where both take all their colours, every pixel in the mean map's lowest fifth (t < 0.2) is
 * bluer than red and every one in its highest fifth redder than blue; in the Gauss map, every
 * pixel with K > 0.2 range[1] is redder than blue, every one with K < 0.2 range[0] bluer. The
 * lighting scales the three channels alike and adds the same white to each, so it keeps the
 * order of R and B; silhouette pixels, darkened by the outline, are left out. */
static void curvature_colours(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    for (int g = 0; g < 2; g++) {
        rg2_render_opts o = kept_opts(240, 160);
        o.mode = g ? RG2_RENDER_GAUSS : RG2_RENDER_MEAN;
        rg2_image img;
        CHECK_OK(rg2_render(&s, 1, NULL, &o, &img, &err), &err);
        int low = 0, high = 0, wrong = 0;
        for (int k = 0; img.pixels && k < img.width * img.height; k++) {
            const rg2_pixel *p = &img.pixels[k];
            if (p->surf < 0 || at_silhouette(&img, k))
                continue;
            const unsigned char *c = img.rgb + 3 * (size_t)k;
            double t = ((g ? p->K : p->H) - img.range[0]) / (img.range[1] - img.range[0]);
            if (t < (g ? 0.4 : 0.2))
                low++, wrong += !(c[2] > c[0]);
            else if (t > (g ? 0.6 : 0.8))
                high++, wrong += !(c[0] > c[2]);
        }
        /* and the bar beside the view (rows 40 (t = 1) .. height - 40 (t = 0), columns width - 98 .. - 77):
         * the mean bar violet at the bottom (B > R > G), green in the middle, red at the top (R above G
         * and B by 100 or more), the Gauss bar blue, grey and red */
        int W = img.width, top = 40, bot = img.height - 40, bar_off = 0;
        for (int x = W - 98; img.rgb && x < W - 76; x++) {
            const unsigned char *b = img.rgb + 3 * ((size_t)bot * W + x), *t = img.rgb + 3 * ((size_t)top * W + x);
            const unsigned char *mid = img.rgb + 3 * ((size_t)(top + bot) / 2 * W + x);
            int red_top = t[0] > t[1] + 100 && t[0] > t[2] + 100;
            bar_off += g ? !(b[2] > b[0] + 100 && abs(mid[0] - mid[2]) < 3 && t[0] > t[2] + 100)
                         : !(b[2] > b[0] && b[0] > b[1] && mid[1] > mid[0] && mid[1] > mid[2] && red_top);
        }
        printf("%s map of the torus: %d pixels at the low end (blue or violet), %d at the high end (red), %d of "
               "another colour\n", g ? "Gauss" : "mean", low, high, wrong);
        CHECK(!bar_off, "%s map: %d columns of the colour bar not %s at the bottom, middle and top", g ? "Gauss" : "mean",
              bar_off, g ? "blue, grey and red" : "violet, green and red");
        CHECK(low > 500 && high > 500 && !wrong, "%s map: %d of %d pixels at the ends of the range not in the end's "
              "colour", g ? "Gauss" : "mean", wrong, low + high);
        rg2_image_free(&img);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

int main(void)
{
    for (int mixed = 0; mixed < 2; mixed++) {
        sphere_pixels(mixed);
        sphere_poles(mixed);
    }
    mixed_vs_plain();
    design_caps();
    zebra_kinks();
    png_valid_and_deterministic();
    errors();
    options();
    apart();
    many_patches();
    far_mesh_points();
    robust_range();
    zebra_antialias();
    shaded_contrast();
    silhouette_pixels();
    pole_pixels();
    colour_bar_labels();
    bar_arrows();
    polar_views();
    low_picture_bar();
    mesh_off_bar();
    small_boundaries();
    stripes_per_turn();
    mesh_legs();
    flat_range();
    overflowing_patch();
    curvature_colours();
    return rg2t_done("test_render");
}
