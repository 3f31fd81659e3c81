/* cavelight-bench frame: milliseconds per pass of the render node (frame pass and one
 * mono eye pass) on a scene, and the GI method's share of the frame. With --gi vpl the
 * frame pass's stages are RSM, selection (RSM readback and choice) and shadow maps, and
 * the gather is the eye pass's host time less that of the same frames with --gi none,
 * measured in the same run (host clocks: llvmpipe's timer queries of a long pass can
 * exceed the host time around it). GPU passes use the
 * renderer's timer queries (read late, never stalling), the rest host clocks. The first
 * two frames are warm-up and not counted. `--scene bunny` is the Stanford bunny from
 * ../shared/scenes/bunny beside the source tree; it is skipped with a message if absent. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "frame/frame_params.h"
#include "glctx.h"
#include "frame/frame_view.h"
#include "renderer.h"
#include "scene/scene.h"

enum { WARMUP = 2, PASSES = 8 };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* <source>/../shared/scenes/bunny/bunny.gltf, the source folder found from this file. */
static void bunny_path(char *out, size_t n)
{
    const char *file = __FILE__, *cut = strstr(file, "/tests/bench/");
    int len = cut ? (int)(cut - file) : 1;
    snprintf(out, n, "%.*s/../shared/scenes/bunny/bunny.gltf", len, cut ? file : ".");
}

int bench_frame(int argc, char **argv)
{
    const char *scene_arg = "default", *gl_name = "egl";
    int width = 320, height = 240, frames = 10, rsm = 256, lattice = 32;
    renderer_lpv_backend lpv = RENDERER_LPV_AUTO;
    renderer_tiles tiles = RENDERER_TILES_AUTO;
    frame_gi gi = FRAME_GI_ILPV;
    int vpl_count = 0;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--scene") == 0) scene_arg = argv[i + 1];
        else if (strcmp(argv[i], "--width") == 0) width = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--height") == 0) height = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--frames") == 0) frames = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--rsm") == 0) rsm = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--lattice") == 0) lattice = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--gl") == 0) gl_name = argv[i + 1];
        else if (strcmp(argv[i], "--vpl-count") == 0) vpl_count = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--gi") == 0) {
            if (frame_gi_parse(argv[i + 1], &gi) != 0) {
                fprintf(stderr, "bench frame: --gi %s: use " FRAME_GI_NAMES "\n", argv[i + 1]);
                return 2;
            }
        }
        else if (strcmp(argv[i], "--tiles") == 0)
            tiles = strcmp(argv[i + 1], "on") == 0 ? RENDERER_TILES_ON
                    : strcmp(argv[i + 1], "off") == 0 ? RENDERER_TILES_OFF : RENDERER_TILES_AUTO;
        else if (strcmp(argv[i], "--lpv") == 0)
            lpv = strcmp(argv[i + 1], "gl") == 0 ? RENDERER_LPV_GL
                  : strcmp(argv[i + 1], "cpu") == 0 ? RENDERER_LPV_CPU : RENDERER_LPV_AUTO;
        else {
            fprintf(stderr, "bench frame: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    if (width < 1 || height < 1 || frames <= WARMUP) {
        fprintf(stderr, "bench frame: need a positive size and more than %d frames\n", WARMUP);
        return 2;
    }
    char path[4096], err[512];
    snprintf(path, sizeof path, "%s", scene_arg);
    if (strcmp(scene_arg, "bunny") == 0) {
        bunny_path(path, sizeof path);
        if (access(path, R_OK) != 0) {
            printf("{\"bench\":\"frame\",\"scene\":\"bunny\",\"skipped\":\"%s not found\"}\n", path);
            return 0;
        }
    }
    glctx_backend backend;
    if (glctx_parse_backend(gl_name, &backend) != 0) {
        fprintf(stderr, "bench frame: --gl egl|osmesa|glfw\n");
        return 2;
    }
    scene sc;
    if (scene_load(path, &sc, err, sizeof err) != 0) {
        fprintf(stderr, "bench frame: %s\n", err);
        return 1;
    }
    glctx_desc gd = {.backend = backend, .width = width, .height = height};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    if (!ctx) {
        fprintf(stderr, "bench frame: %s\n", err);
        scene_free(&sc);
        return 1;
    }
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = &sc, .lpv_backend = lpv,
                        .rsm_size = rsm, .lattice_cells = lattice, .lpv_gl_tiles = tiles,
                        .converge_threshold = -1, .gi = gi}; /* static frames: measure the work, never skip */
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r) {
        fprintf(stderr, "bench frame: %s\n", err);
        glctx_destroy(ctx);
        scene_free(&sc);
        return 1;
    }
    frame_params fp;
    frame_params_default(&fp);
    frame_params_lights_from_scene(&fp, &sc);
    fp.gi = gi;
    if (vpl_count)
        fp.vpl_count = vpl_count;
    frame_params_sanitize(&fp); /* the count reported is the one rendered */
    renderer_view v;
    float eye[3], target[3];
    scene_default_view(&sc, eye, target);
    frame_view_camera(eye, target, scene_default_yfov(&sc), scene_far_plane(&sc), width, height,
                      &v);

    int n = frames - WARMUP;
    double *s = calloc((size_t)n * (PASSES + 1), sizeof *s);
    if (!s) {
        fprintf(stderr, "bench frame: out of memory\n");
        return 1;
    }
    int rc = 0;
    for (int f = 0; f < frames && rc == 0; f++) {
        renderer_frame_pass(r, &fp);
        renderer_image img;
        rc = renderer_eye_pass(r, &v, 0, &img);
        renderer_timings t;
        renderer_get_timings(r, &t);
        if (f < WARMUP)
            continue;
        double vals[PASSES] = {t.rsm_ms, t.inject_ms, t.propagate_ms, t.gbuffer_ms,
                               t.shade_ms, t.final_ms, t.frame_host_ms, t.eye_host_ms};
        for (int p = 0; p < PASSES; p++)
            s[(size_t)p * n + (f - WARMUP)] = vals[p];
    }
    /* vpl: the same frames without indirect light: the eye pass less the gather. */
    double *base = s + (size_t)PASSES * n;
    frame_params direct_only = fp;
    direct_only.gi = FRAME_GI_NONE;
    for (int f = 0; f < frames && rc == 0 && gi == FRAME_GI_VPL; f++) {
        renderer_frame_pass(r, &direct_only);
        renderer_image img;
        rc = renderer_eye_pass(r, &v, 0, &img);
        renderer_timings t;
        renderer_get_timings(r, &t);
        if (f >= WARMUP)
            base[f - WARMUP] = t.eye_host_ms;
    }
    static const char *lpv_names[PASSES] = {"rsm_ms", "inject_ms", "propagate_ms", "gbuffer_ms",
                                            "shade_ms", "final_ms", "frame_host_ms", "eye_host_ms"};
    static const char *vpl_names[PASSES] = {"rsm_ms", "select_ms", "shadow_ms", "gbuffer_ms",
                                            "shade_ms", "final_ms", "frame_host_ms", "eye_host_ms"};
    const char *const *names = gi == FRAME_GI_VPL ? vpl_names : lpv_names;
    double med[PASSES + 1];
    for (int p = 0; p <= PASSES; p++) {
        qsort(s + (size_t)p * n, (size_t)n, sizeof *s, cmp_double);
        med[p] = n % 2 ? s[(size_t)p * n + n / 2]
                       : 0.5 * (s[(size_t)p * n + n / 2 - 1] + s[(size_t)p * n + n / 2]);
    }
    const lattice_desc *lat = renderer_get_lattice(r);
    if (rc == 0) {
        printf("{\"bench\":\"frame\",\"scene\":\"%s\",\"triangles\":%zu,\"gl\":\"%s\","
               "\"renderer\":\"%s\",\"gi\":\"%s\",\"width\":%d,\"height\":%d,\"rsm\":%d,"
               "\"frames\":%d",
               scene_arg, sc.triangle_count, glctx_describe(ctx), glctx_renderer(ctx),
               frame_gi_name(gi), width, height, rsm, n);
        if (lat)
            printf(",\"lpv\":\"%s\",\"lattice\":[%d,%d,%d],\"steps\":%d",
                   renderer_get_lpv_backend(r) == RENDERER_LPV_GL ? "gl" : "cpu", lat->n[0],
                   lat->n[1], lat->n[2], fp.lpv_steps);
        if (gi == FRAME_GI_VPL)
            printf(",\"vpl_count\":%d", fp.vpl_count);
        for (int p = 0; p < PASSES; p++)
            printf(",\"%s\":%.3f", names[p], med[p]);
        double total = med[6] + med[7], gather = med[7] - med[PASSES];
        if (gi == FRAME_GI_VPL)
            printf(",\"eye_direct_only_ms\":%.3f,\"gather_ms\":%.3f", med[PASSES], gather);
        /* The method's work: injection and propagation, or selection, shadows, gather. */
        double work = med[1] + med[2] + (gi == FRAME_GI_VPL ? gather : 0.0);
        printf(",\"gi_share\":%.3f}\n", total > 0 ? work / total : 0.0);
    } else {
        fprintf(stderr, "bench frame: %s\n", renderer_last_error(r));
    }
    free(s);
    renderer_destroy(r);
    glctx_destroy(ctx);
    scene_free(&sc);
    return rc ? 1 : 0;
}
#else
int bench_frame(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "bench frame: this build has no render node (cavelight_node)\n");
    return 1;
}
#endif
