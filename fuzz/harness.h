/* harness.h -- the fuzz harnesses of rg2, shared by the libFuzzer entry points (fuzz/fuzz_*.c,
 * `make fuzz`) and the corpus replay test (tests/test_fuzz_replay.c, `make test`).
 *
 * Each harness takes arbitrary bytes, runs one whole library path on them and checks the
 * library's contract; a broken contract calls rg2f_violation(), which aborts (the fuzzer
 * records the input as a crash). Sanitizers catch memory errors, leaks and undefined
 * behaviour on the same path. */
#ifndef RG2_FUZZ_HARNESS_H
#define RG2_FUZZ_HARNESS_H

#include <stddef.h>
#include <stdint.h>

/* Name of the input being run (for messages; the replay test sets it), or NULL. */
extern const char *rg2f_input_name;

/* Inputs longer than this are skipped: they only slow the fuzzer down. */
#define RG2F_MAX_INPUT (64 * 1024)

/* The design path: rg2_design_parse -> build meshes -> construct patches -> check the
 * surfaces (finite patches, tags in range, evaluation of every patch, minimum weight, and a
 * coarse tessellation of small surfaces). */
int rg2f_design(const uint8_t *data, size_t size);

/* The NURBS import path: a bi-cubic NURBS decoded from the bytes (sizes, clamping, weights,
 * knots, points) -> rg2_nurbs_mesh -> rg2_surface_build -> checks; for well-conditioned input
 * the built patches are compared with an independent de Boor evaluation of the NURBS. */
int rg2f_nurbs(const uint8_t *data, size_t size);

/* The C mesh operations: 1 to 3 small meshes decoded from the bytes (closed or open, scalars
 * near the uniform ones), then up to 8 operations (cut with any int indices, transpose,
 * reverse, merge of 1 to 3 meshes either way with either seam rule, morph at t in -0.05..1.05)
 * on them and their results: a failure reports itself and leaves its output empty; a result is
 * a mesh that passes rg2_mesh_check, whose surface builds or says why not; transpose twice and
 * a morph at t = 0 give the mesh back, bit for bit. */
int rg2f_meshops(const uint8_t *data, size_t size);

#endif
