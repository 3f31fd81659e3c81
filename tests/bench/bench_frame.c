/* cavelight-bench frame: milliseconds per pass of the render node (frame pass and one
 * mono eye pass) on a scene, and the GI method's share of the frame. With --gi vpl the
 * frame pass's stages are RSM, selection (RSM readback and choice) and shadow maps, and
 * the gather is the eye pass's host time less that of the same frames with --gi none,
 * measured in the same run (host clocks: llvmpipe's timer queries of a long pass can
 * exceed the host time around it); with clustered or tiled lists (--vpl-lights) the light
 * assignment is its own stage, out of the gather, and a stereo pair of eyes from the
 * camera (parallel axes, FRAME_VIEW_EYE_SEPARATION apart) is assigned per eye and
 * enclosed (one grid for both eyes): milliseconds and (VPL, cluster) pairs of each.
 * --vpl-visibility and --vpl-interleave choose the shadow test (shadow_ms is then the
 * imperfect maps' time) and interleaved sampling (its gather and blur are in gather_ms).
 * GPU passes use the
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
#include "lpv/lattice.h"
#include "glctx.h"
#include "present.h"
#include "frame/frame_view.h"
#include "frame/offaxis.h"
#include "renderer.h"
#include "scene/scene.h"
#include "vpl_ism.h"

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
    const char *scene_arg = "default";
    int width = 320, height = 240, frames = 10, rsm = RENDERER_DEFAULT_RSM_SIZE;
    int lattice = LATTICE_DEFAULT_AXIS_CELLS, gl_index = GLCTX_EGL;
    int lpv = RENDERER_LPV_AUTO, tiles = RENDERER_TILES_AUTO, gi_index = FRAME_GI_ILPV;
    int vpl_count = FRAME_VPL_DEFAULT, vpl_lights = RENDERER_VPL_CLUSTERED;
    int visibility = RENDERER_VPL_EXACT, interleave = 0;
    static const char *const gl_names[] = {"egl", "osmesa", "glfw"};
    static const char *const lpv_names[] = {"auto", "cpu", "gl"};
    static const char *const tiles_names[] = {"auto", "on", "off"};
    static const char *const lights_names[] = {"clustered", "tiled", "all"};
    const bench_option opts[] = {
        BENCH_TEXT("scene", "default|bunny|FILE", "scene (bunny: ../shared/scenes/bunny)", &scene_arg),
        BENCH_INT("width", "W", "image width", &width, 1, 16384),
        BENCH_INT("height", "H", "image height", &height, 1, 16384),
        BENCH_INT("frames", "N", "frames (the first ones warm up)", &frames, WARMUP + 1, 1000000),
        BENCH_INT("rsm", "N", "reflective shadow map size", &rsm, 8, 4096),
        BENCH_INT("lattice", "N", "LPV cells along the longest axis", &lattice, 2, 512),
        BENCH_CHOICE("gl", "egl|osmesa|glfw", "GL context", &gl_index, gl_names),
        BENCH_CHOICE("lpv", "auto|cpu|gl", "where the LPV runs", &lpv, lpv_names),
        BENCH_CHOICE("tiles", "auto|on|off", "GL propagation tiles", &tiles, tiles_names),
        BENCH_CHOICE("gi", "ilpv|none|vpl", "indirect-light method", &gi_index, frame_gi_names),
        BENCH_INT("vpl-count", "N", "vpl: lights per frame", &vpl_count, FRAME_VPL_MIN, FRAME_VPL_MAX),
        BENCH_CHOICE("vpl-lights", "clustered|tiled|all", "vpl: light assignment of the gather",
                     &vpl_lights, lights_names),
        BENCH_CHOICE("vpl-visibility", "exact|ism|ism-splat", "vpl: shadow test of the VPLs",
                     &visibility, vpl_visibility_names),
        BENCH_INT("vpl-interleave", "K", "vpl: interleaved sampling in K x K blocks (0: off)",
                  &interleave, 0, RENDERER_VPL_INTERLEAVE_MAX),
    };
    int pr = BENCH_PARSE("frame", "frame and eye passes of the renderer", opts, argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    const char *gl_name = gl_names[gl_index];
    frame_gi gi = (frame_gi)gi_index;
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
    /* glfw: the context of a window, as a node's window output makes it (present.h). */
    present_viewport pv = {.name = "bench", .width = width, .height = height};
    present_desc pd = {.output = backend == GLCTX_GLFW ? PRESENT_WINDOW : PRESENT_HEADLESS, .backend = backend,
                       .log_name = "bench frame", .quiet = 1, .viewport_count = 1, .viewports = &pv};
    present *out = present_create(&pd, err, sizeof err);
    glctx *ctx = out ? present_context(out) : NULL;
    if (!ctx) {
        fprintf(stderr, "bench frame: %s\n", err);
        scene_free(&sc);
        return 1;
    }
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = &sc, .lpv_backend = lpv,
                        .rsm_size = rsm, .lattice_cells = lattice, .lpv_gl_tiles = tiles,
                        .converge_threshold = -1, .gi = gi, /* static frames: measure the work, never skip */
                        .vpl_lights = (renderer_vpl_lights)vpl_lights,
                        .vpl_visibility = (renderer_vpl_visibility)visibility,
                        .vpl_interleave = interleave};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r) {
        fprintf(stderr, "bench frame: %s\n", err);
        present_destroy(out);
        scene_free(&sc);
        return 1;
    }
    frame_params fp;
    frame_params_default(&fp);
    frame_params_lights_from_scene(&fp, &sc);
    fp.gi = gi;
    fp.vpl_count = vpl_count;
    renderer_view v;
    scene_camera cam;
    scene_default_camera(&sc, &cam);
    frame_view_scene_camera(&cam, cam.position, scene_far_plane(&sc), width, height, &v);

    int n = frames - WARMUP;
    double *s = calloc((size_t)n * (PASSES + 1), sizeof *s);
    if (!s) {
        fprintf(stderr, "bench frame: out of memory\n");
        return 1;
    }
    int rc = 0;
    double *assign = calloc((size_t)n * 3, sizeof *assign); /* mono, per eye, enclosed */
    size_t pairs[3] = {0, 0, 0};
    for (int f = 0; f < frames && rc == 0; f++) {
        renderer_frame_pass(r, &fp);
        renderer_image img;
        rc = renderer_eye_pass(r, &v, 0, &img);
        renderer_timings t;
        renderer_get_timings(r, &t);
        if (f < WARMUP)
            continue;
        assign[f - WARMUP] = t.assign_ms;
        pairs[0] = t.assignments;
        double vals[PASSES] = {t.rsm_ms, t.inject_ms, t.propagate_ms, t.gbuffer_ms,
                               t.shade_ms, t.final_ms, t.frame_host_ms, t.eye_host_ms};
        for (int p = 0; p < PASSES; p++)
            s[(size_t)p * n + (f - WARMUP)] = vals[p];
    }
    /* vpl: a stereo pair from the camera, assigned per eye and then enclosed. */
    renderer_view pair[2];
    float right[3] = {1, 0, 0}, view_m[16];
    if (offaxis_view(cam.position, cam.target, cam.up, view_m) == 0)
        for (int i = 0; i < 3; i++)
            right[i] = view_m[4 * i];
    for (int e = 0; e < 2; e++) {
        float eye[3];
        frame_view_eye(cam.position, right, FRAME_VIEW_EYE_SEPARATION, 2 * e - 1, eye);
        frame_view_scene_camera(&cam, eye, scene_far_plane(&sc), width, height, &pair[e]);
    }
    for (int f = 0; f < frames && rc == 0 && gi == FRAME_GI_VPL; f++) {
        renderer_frame_pass(r, &fp);
        for (int enclosed = 0; enclosed < 2 && rc == 0; enclosed++) {
            if (enclosed)
                renderer_screen(r, pair, 2);
            double ms = 0;
            size_t count = 0;
            for (int e = 0; e < 2 && rc == 0; e++) {
                renderer_image img;
                rc = renderer_eye_pass(r, &pair[e], 0, &img);
                renderer_timings t;
                renderer_get_timings(r, &t);
                if (e == 0 || !enclosed) { /* enclosed: the screen's one assignment */
                    ms += t.assign_ms;
                    count += t.assignments;
                }
            }
            if (f >= WARMUP) {
                assign[(size_t)(1 + enclosed) * n + (f - WARMUP)] = ms;
                pairs[1 + enclosed] = count;
            }
        }
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
    static const char *lpv_passes[PASSES] = {"rsm_ms", "inject_ms", "propagate_ms", "gbuffer_ms",
                                             "shade_ms", "final_ms", "frame_host_ms", "eye_host_ms"};
    static const char *vpl_passes[PASSES] = {"rsm_ms", "select_ms", "shadow_ms", "gbuffer_ms",
                                             "shade_ms", "final_ms", "frame_host_ms", "eye_host_ms"};
    const char *const *names = gi == FRAME_GI_VPL ? vpl_passes : lpv_passes;
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
            printf(",\"vpl_count\":%d,\"vpl_lights\":\"%s\",\"vpl_visibility\":\"%s\","
                   "\"vpl_interleave\":%d", fp.vpl_count, lights_names[vpl_lights],
                   vpl_visibility_names[visibility], interleave);
        for (int p = 0; p < PASSES; p++)
            printf(",\"%s\":%.3f", names[p], med[p]);
        double am[3];
        for (int k = 0; k < 3; k++) {
            qsort(assign + (size_t)k * n, (size_t)n, sizeof *assign, cmp_double);
            am[k] = n % 2 ? assign[(size_t)k * n + n / 2]
                          : 0.5 * (assign[(size_t)k * n + n / 2 - 1] + assign[(size_t)k * n + n / 2]);
        }
        double total = med[6] + med[7], gather = med[7] - med[PASSES] - am[0];
        if (gi == FRAME_GI_VPL)
            printf(",\"eye_direct_only_ms\":%.3f,\"assign_ms\":%.3f,\"gather_ms\":%.3f,"
                   "\"assignments\":%zu,\"stereo_assign_per_eye_ms\":%.3f,"
                   "\"stereo_assign_enclosed_ms\":%.3f,\"stereo_assignments_per_eye\":%zu,"
                   "\"stereo_assignments_enclosed\":%zu,\"enclosed_fewer\":%.3f",
                   med[PASSES], am[0], gather, pairs[0], am[1], am[2], pairs[1], pairs[2],
                   pairs[1] ? 1.0 - (double)pairs[2] / (double)pairs[1] : 0.0);
        /* The method's work: injection and propagation, or selection, shadows, gather. */
        double work = med[1] + med[2] + (gi == FRAME_GI_VPL ? am[0] + gather : 0.0);
        printf(",\"gi_share\":%.3f}\n", total > 0 ? work / total : 0.0);
    } else {
        fprintf(stderr, "bench frame: %s\n", renderer_last_error(r));
    }
    free(s);
    free(assign);
    renderer_destroy(r);
    present_destroy(out);
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
