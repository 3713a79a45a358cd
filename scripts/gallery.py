#!/usr/bin/env python3
"""make gallery: render every example design and write docs/gallery.md.

For each design in examples/ this renders two pictures with the rg2 command (shaded with the
patch boundaries, exact pieces tinted by their shape; and the mean curvature, which shows a
curvature-continuous surface as continuous colour), runs `rg2 check --json` for the measured
figures (exact patches and their worst residual, the worst G1 and G2 gaps over all patch seams,
the smallest weight), and writes the page with the design's own description.

Usage: scripts/gallery.py RG2 [OUT_DIR]   (OUT_DIR defaults to docs; pictures go to
OUT_DIR/pictures/gallery/, the page to OUT_DIR/gallery.md)
"""
import json
import os
import subprocess
import sys

SIZE = "400x300"
# Designs whose output surfaces lie on top of each other are laid out apart (rg2 render --apart).
PICTURES = {
    "fig1_torus": [("shaded", ["--apart", "--boundaries"],
                    "(a), (c) above, (e), (f) below (--apart): shaded, patch boundaries"),
                   ("mean", ["--apart", "--mode", "mean"], "mean curvature: only (e) and (f) leave the torus")],
}
DEFAULT = [("shaded", ["--boundaries"], "shaded, patch boundaries; exact pieces tinted by shape"),
           ("mean", ["--mode", "mean"], "mean curvature")]


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit("gallery: %s failed (exit %d): %s" % (" ".join(cmd), r.returncode, r.stderr.strip()))
    return r.stdout


def figures(rep):
    exact = ", ".join("%s %d" % (s["label"], s["patches"]) for s in rep["shapes"] if s["patches"]) or "none"
    g1, g2 = rep["g1_normal_angle"], rep["g2_curvature_jump"]
    row = ["%d" % rep["surfaces"], "%d" % rep["patches"],
           "%d (%s)" % (rep["exact_patches"], exact), "%d" % rep["transitions"],
           "%.1e" % rep["worst_residual"] if rep["exact_patches"] else "-",
           "%.1e rad" % g1["value"], "%.1e" % g2["value"]]
    ok = all(x["ok"] for x in (rep["g0_position"], g1, g2)) and all(s["ok"] for s in rep["shapes"])
    return row, ok


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    rg2 = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else "docs"
    pics = os.path.join(out, "pictures", "gallery")
    os.makedirs(pics, exist_ok=True)
    names = sorted((f[:-5] for f in os.listdir("examples") if f.endswith(".json")),
                   key=lambda n: (0, int(n[3:].split("_")[0])) if n.startswith("fig") else (1, n))
    lines = ["# Gallery: the example designs",
             "",
             "Every design in `examples/`, rendered from the exact surface by `rg2 render` (%s pixels), "
             "with the figures `rg2 check` measures on it: the exact pieces' worst implicit residual "
             "(relative to the shape's size), and the worst G1 (normal angle) and G2 (normal-curvature "
             "jump, relative) gaps over the samples of every patch seam; next to a pole, samples whose "
             "rounding bound exceeds the limits are measured against that bound instead and are not in "
             "these two columns ([poles.md](poles.md#measured-seams-worst-over-the-tests), \"How `rg2 check` treats poles\"). \"Exact\" "
             "counts the patches tagged with a shape by their provenance ([design-format.md]"
             "(design-format.md#provenance-which-patches-are-exact)); a transition patch may lie on a "
             "shape too. Shaded pictures tint the "
             "patches that are exact pieces of a shape (one colour per shape) and leave the transition "
             "patches grey-blue; the mean-curvature pictures show a curvature-continuous surface as "
             "continuous colour." % SIZE.replace("x", " x "),
             "",
             "Made by `make gallery` (`scripts/gallery.py`); the figures are this build's, on this "
             "machine (the last bits of the gaps can differ between builds and CPUs).",
             "",
             "| design | surfaces | patches | exact (per shape) | transition | worst residual | G1 | G2 |",
             "|---|---|---|---|---|---|---|---|"]
    sections = []
    for n in names:
        path = "examples/%s.json" % n
        with open(path) as f:
            desc = json.load(f).get("description", "")
        rep = json.loads(run([rg2, "check", path, "--json"]))
        row, ok = figures(rep)
        if not ok:
            sys.exit("gallery: %s fails its check" % path)
        lines.append("| [`%s`](#%s) | %s |" % (n, n, " | ".join(row)))
        cells, caps = [], []
        for tag, opts, cap in PICTURES.get(n, DEFAULT):
            png = os.path.join(pics, "%s-%s.png" % (n, tag))
            run([rg2, "render", path, "-o", png, "--size", SIZE, "--threads", "1"] + opts)
            cells.append("![%s %s](pictures/gallery/%s-%s.png)" % (n, tag, n, tag))
            caps.append(cap)
        cmds = ["`rg2 render %s -o %s-%s.png --size %s %s`" % (path, n, tag, SIZE, " ".join(opts))
                for tag, opts, _ in PICTURES.get(n, DEFAULT)]  # (the pictures' own commands, bit for bit)
        sections += ["", "## %s" % n, "", desc, "",
                     "| " + " | ".join(caps) + " |", "|" + "---|" * len(caps), "| " + " | ".join(cells) + " |",
                     "", "  \n".join(cmds)]  # (two spaces: a Markdown line break)
    with open(os.path.join(out, "gallery.md.tmp"), "w") as f:
        f.write("\n".join(lines + sections) + "\n")
    os.replace(os.path.join(out, "gallery.md.tmp"), os.path.join(out, "gallery.md"))
    print("gallery: %d designs, %s/gallery.md" % (len(names), out))


if __name__ == "__main__":
    main()
