/* Shared by the accuracy subcommands of cavelight-bench (bench_accuracy*.c): one scene,
 * one GL context and one camera per run, the path-traced reference for a light setting
 * (rendered once and cached as PFMs in the output folder), and the measurements every
 * experiment takes of a rendered frame. */
#ifndef CAVELIGHT_BENCH_ACCURACY_H
#define CAVELIGHT_BENCH_ACCURACY_H

#include <stdint.h>
#include <stdio.h>

#include "frame/frame_params.h"
#include "gi/gi_settings.h"
#include "gi/ilpv/gi_ilpv.h"
#include "gl/glctx.h"
#include "image/image_metrics.h"
#include "renderer.h"
#include "scene/scene.h"

typedef struct acc_options {
    const char *scene;      /* a built-in scene's name or a glTF path */
    const char *out;        /* folder for CSVs and the cached reference */
    int width, height;
    int ref_samples;        /* paths per pixel of each of the two reference halves (the
                               first round's, with ref_noise) */
    const char *ref_noise;  /* "0", or the noise relRMSE to render more rounds down to */
    int threads;            /* CPU LPV threads, 0 = all */
} acc_options;

typedef struct acc_setup {
    acc_options opt;
    double ref_noise;       /* opt.ref_noise as a number */
    scene sc;
    glctx *ctx;
    renderer_view view;
    frame_params base;      /* the scene's lights and the renderer's defaults */
    float encoding_gamma;
} acc_setup;

/* The reference for one light setting: linear images and their tone-mapped display. */
typedef struct acc_reference {
    float *direct, *indirect1, *final1; /* final1 = direct + indirect1: what the LPV models */
    uint8_t *coverage;                  /* 1 where a pixel meets geometry: the metrics' mask */
    uint8_t *display;                   /* final1 tone-mapped like shaders/final.frag */
    double noise_indirect1;             /* MAE of the averaged indirect1 (from its halves) */
    double noise_rms_indirect1;         /* its RMS over the covered pixels */
    double mean_indirect1;
    double noise_rel;                   /* noise_rms_indirect1 over indirect1's mean on the
                                           covered pixels: the reference's own relRMSE */
    double seconds;                     /* render time (when it was rendered) */
    int samples;                        /* paths per pixel of each half */
    int cached;                         /* read from the cache, not rendered now */
} acc_reference;

/* Parses the options every accuracy subcommand takes; returns 1 if argv[*i] was one. */
int acc_parse_common(acc_options *o, int argc, char **argv, int *i, int *bad);
/* The same options as rows of a bench_option table (bench.h), for an experiment whose
 * command line is a table: its --help then lists them. */
#define ACC_COMMON_OPTIONS(o)                                                                  \
    BENCH_TEXT("scene", "NAME|FILE", "a built-in scene or a glTF file", &(o)->scene),         \
    BENCH_TEXT("out", "DIR", "folder for the CSVs and the cached reference", &(o)->out),      \
    BENCH_INT("width", "W", "image width", &(o)->width, 8, 16384),                            \
    BENCH_INT("height", "H", "image height", &(o)->height, 8, 16384),                         \
    BENCH_INT("ref-samples", "N", "paths per pixel of each of the reference's two halves",    \
              &(o)->ref_samples, 1, 1 << 20),                                                  \
    BENCH_TEXT("ref-noise", "T", "add rounds of paths until the reference's noise relRMSE\n"  \
               "is at most T (0: one round of --ref-samples)", &(o)->ref_noise),              \
    BENCH_INT("threads", "T", "CPU LPV threads (0: all cores)", &(o)->threads, 0, 1024)
int acc_setup_open(acc_setup *s, const acc_options *o);
void acc_setup_close(acc_setup *s);

/* tag names the light setting in the cache's file names (e.g. "a", "moved"). */
int acc_reference_get(acc_setup *s, const frame_params *p, const char *tag, acc_reference *out);
void acc_reference_free(acc_reference *r);

enum { ACC_FITTED = 0, ACC_FITTED_CELLS = 32 * 32 * 32 };

typedef struct acc_renderer_desc {
    ilpv_backend_choice backend;
    int lattice;            /* cells along the longest axis; ACC_FITTED: a cube's worth of
                               cells (ACC_FITTED_CELLS) spent on the scene's shape */
    int classic;            /* sum every step into an accumulation lattice (KD10) */
    lpv_transport transport; /* --lpv-transport (0: beams) */
    int skip_converged;     /* let the renderer skip work once converged */
    const char *gi;         /* the method ("ilpv" when NULL) */
    int vpl_point;          /* vpl: VPLs as points, unbounded (vpl-bound point) */
    const char *vpl_visibility; /* vpl: "exact" when NULL, "ism", "ism-splat" */
    int ism_size, ism_points;   /* 0: the defaults */
    float vpl_cut;          /* vpl: influence cut; 0: the default */
    int vpl_interleave;     /* vpl: K x K interleaving, 0: none */
} acc_renderer_desc;
/* A renderer for d; d's settings are written into fp (the frames it renders must carry
 * them: the frames decide the GI method and its settings). NULL after one line. */
renderer *acc_renderer_create(acc_setup *s, const acc_renderer_desc *d, frame_params *fp);

/* Mean HDR-FLIP (common/image/flip.h) of an indirect image against the reference's
 * one-bounce image over its covered pixels; NaN when it cannot be taken. */
double acc_flip(const acc_setup *s, const acc_reference *ref, const float *indirect);
/* Mean absolute difference of two 8-bit images, in [0, 1]. */
double acc_display_mae(const uint8_t *a, const uint8_t *b, size_t pixels);
/* Mean absolute difference of two linear float images. */
double acc_linear_mae(const float *a, const float *b, size_t pixels);
double acc_median(double *v, int n);
/* One frame of fp: r's frame pass, its eye pass of the first view into img (indirect kept)
 * and its timings into t; -1 after one line that names the bench (what). */
int acc_frame(acc_setup *s, renderer *r, const frame_params *fp, const char *what,
              renderer_image *img, renderer_timings *t);
FILE *acc_open_csv(const acc_setup *s, const char *name, const char *header);
/* Frames until the history's weight lambda^k falls below 1e-3: the steady state. */
int acc_warm_frames(float lambda);

/* The subcommands (bench_accuracy_motion.c, bench_accuracy_savings.c). */
int accuracy_move(int argc, char **argv);
int accuracy_path(int argc, char **argv);
int accuracy_savings(int argc, char **argv);
int accuracy_vpl(int argc, char **argv);
int accuracy_caches(int argc, char **argv);
int accuracy_ldm(int argc, char **argv);
int accuracy_reference(int argc, char **argv);

#endif
