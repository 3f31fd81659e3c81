/* cavelight-bench frame: milliseconds per pass of the render node (frame pass and one
 * mono eye pass) on a scene, and the LPV's share of the frame. GPU passes use the
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
    for (int i = 1; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--scene") == 0) scene_arg = argv[i + 1];
        else if (strcmp(argv[i], "--width") == 0) width = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--height") == 0) height = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--frames") == 0) frames = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--rsm") == 0) rsm = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--lattice") == 0) lattice = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--gl") == 0) gl_name = argv[i + 1];
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
                        .converge_threshold = -1}; /* static frames: measure the work, never skip */
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
    renderer_view v;
    scene_camera cam;
    scene_default_camera(&sc, &cam);
    frame_view_scene_camera(&cam, cam.position, scene_far_plane(&sc), width, height, &v);

    int n = frames - WARMUP;
    double *s = calloc((size_t)n * PASSES, sizeof *s);
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
    static const char *names[PASSES] = {"rsm_ms", "inject_ms", "propagate_ms", "gbuffer_ms",
                                        "shade_ms", "final_ms", "frame_host_ms", "eye_host_ms"};
    double med[PASSES];
    for (int p = 0; p < PASSES; p++) {
        qsort(s + (size_t)p * n, (size_t)n, sizeof *s, cmp_double);
        med[p] = n % 2 ? s[(size_t)p * n + n / 2]
                       : 0.5 * (s[(size_t)p * n + n / 2 - 1] + s[(size_t)p * n + n / 2]);
    }
    const lattice_desc *lat = renderer_get_lattice(r);
    if (rc == 0) {
        printf("{\"bench\":\"frame\",\"scene\":\"%s\",\"triangles\":%zu,\"gl\":\"%s\","
               "\"renderer\":\"%s\",\"lpv\":\"%s\",\"width\":%d,\"height\":%d,\"rsm\":%d,"
               "\"lattice\":[%d,%d,%d],\"steps\":%d,\"frames\":%d",
               scene_arg, sc.triangle_count, glctx_describe(ctx), glctx_renderer(ctx),
               renderer_get_lpv_backend(r) == RENDERER_LPV_GL ? "gl" : "cpu", width, height,
               rsm, lat->n[0], lat->n[1], lat->n[2], fp.lpv_steps, n);
        for (int p = 0; p < PASSES; p++)
            printf(",\"%s\":%.3f", names[p], med[p]);
        double total = med[6] + med[7];
        printf(",\"lpv_share\":%.3f}\n", total > 0 ? (med[1] + med[2]) / total : 0.0);
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
