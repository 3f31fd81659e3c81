/* cavelight-bench move: what moving one scene object costs each GI method's frame pass.
 * For every method of the registry, a renderer on the scene (every frame computed: no
 * reuse, so that a static frame costs its work too) renders frames in pairs: one where
 * the object moved (a new offset every pair), one where nothing changed, in alternating
 * order; the medians of
 * the frame pass's host time of both, their difference (the extra cost of moving), and
 * what the method spends following the object itself (its "objects_ms" figure: ILPV's
 * blockers, lpv_objects.h) with the cells it redid. (A node reuses a converged ILPV
 * frame when nothing changed, 0 ms; a frame in which an object moved is computed whole:
 * moving_ms is then what the object costs.) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "frame/frame_view.h"
#include "gi/gi_settings.h"
#include "gl/glctx.h"
#include "renderer.h"
#include "scene/scene_load.h"

enum { WARMUP = 2 };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct move_result {
    double still_ms, moving_ms, objects_ms, cells;
} move_result;

/* pairs of frames of method m: moved, then unchanged. -1 when the renderer fails. */
static int measure(glctx *ctx, const scene *sc, int object, frame_params fp, int m, int pairs, int w, int h,
                   move_result *out)
{
    char err[300];
    fp.gi = m;
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = sc, .first = &fp, .no_reuse = 1};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r) {
        fprintf(stderr, "bench move: %s\n", err);
        return -1;
    }
    renderer_view v;
    scene_camera cam;
    scene_default_camera(sc, &cam);
    frame_view_scene_camera(&cam, cam.position, scene_far_plane(sc), w, h, &v);
    double *t = calloc((size_t)pairs * 4, sizeof *t);
    scene_pose pose;
    scene_pose_rest(sc, &pose);
    int rc = 0;
    for (int i = 0; i < WARMUP + pairs && rc == 0; i++)
        for (int j = 0; j < 2 && rc == 0; j++) {
            /* The order alternates: the first frame after an eye pass runs slower on
             * llvmpipe, whatever moved (a fixed order put 13 ms on that side). */
            int moved = j == i % 2;
            if (moved) /* 10 cm back and forth along x, a new place every pair */
                pose.offset[object][12] = 0.1f * sinf(0.7f * (float)i);
            renderer_set_pose(r, &pose);
            renderer_frame_pass(r, &fp);
            renderer_image img;
            rc = renderer_eye_pass(r, &v, 0, &img);
            renderer_timings tm;
            renderer_get_timings(r, &tm);
            if (i < WARMUP)
                continue;
            int k = i - WARMUP;
            t[(size_t)(moved ? 1 : 0) * pairs + k] = tm.frame_host_ms;
            if (moved) {
                t[(size_t)2 * pairs + k] = gi_stats_value(&tm.gi, "objects_ms", NULL);
                t[(size_t)3 * pairs + k] = gi_stats_value(&tm.gi, "objects_cells", NULL);
            }
        }
    if (rc == 0)
        *out = (move_result){median(t, pairs), median(t + pairs, pairs), median(t + 2 * pairs, pairs),
                             median(t + 3 * pairs, pairs)};
    free(t);
    renderer_destroy(r);
    return rc ? -1 : 0;
}

int bench_move(int argc, char **argv)
{
    const char *scene_arg = "default", *object_arg = "tall_box";
    int width = 160, height = 120, pairs = 10;
    frame_params fp;
    frame_params_default(&fp);
    const bench_option opts[] = {
        BENCH_TEXT("scene", "NAME|FILE", "a built-in scene or a glTF file", &scene_arg),
        BENCH_TEXT("object", "NAME", "the object that moves", &object_arg),
        BENCH_INT("width", "W", "image width", &width, 1, 16384),
        BENCH_INT("height", "H", "image height", &height, 1, 16384),
        BENCH_INT("pairs", "N", "measured pairs of frames (moved, unchanged) per method", &pairs, 1, 100000),
        BENCH_SETTINGS(&fp),
    };
    int pr = BENCH_PARSE("move", "each GI method's extra frame-pass time when an object moves", opts, argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    char err[512];
    scene sc;
    if (scene_load(scene_arg, &sc, err, sizeof err) != 0) {
        fprintf(stderr, "bench move: %s\n", err);
        return 1;
    }
    int object = scene_object_find(&sc, object_arg);
    glctx *ctx = object >= 0 ? glctx_create(&(glctx_desc){.backend = GLCTX_EGL}, err, sizeof err) : NULL;
    if (!ctx) {
        fprintf(stderr, "bench move: %s\n", object < 0 ? "no such object in the scene (--object)" : err);
        scene_free(&sc);
        return 1;
    }
    frame_params_lights_from_scene(&fp, &sc);
    printf("{\"bench\":\"move\",\"scene\":\"%s\",\"object\":\"%s\",\"renderer\":\"%s\",\"width\":%d,"
           "\"height\":%d,\"pairs\":%d,\"methods\":[", scene_arg, object_arg, glctx_renderer(ctx), width, height,
           pairs);
    int rc = 0;
    for (int m = 0; m < gi_method_count() && rc == 0; m++) {
        move_result res;
        rc = measure(ctx, &sc, object, fp, m, pairs, width, height, &res);
        if (rc == 0)
            printf("%s{\"gi\":\"%s\",\"still_ms\":%.3f,\"moving_ms\":%.3f,\"extra_ms\":%.3f,\"extra\":%.3f,"
                   "\"objects_ms\":%.3f,\"objects_cells\":%.0f}", m ? "," : "", gi_method_at(m)->name,
                   res.still_ms, res.moving_ms, res.moving_ms - res.still_ms,
                   res.still_ms > 0 ? res.moving_ms / res.still_ms - 1.0 : 0.0, res.objects_ms, res.cells);
    }
    printf("]}\n");
    glctx_destroy(ctx);
    scene_free(&sc);
    return rc ? 1 : 0;
}
#else
int bench_move(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "bench move: this build has no render node (cavelight_node)\n");
    return 1;
}
#endif
