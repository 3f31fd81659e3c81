/* cavelight-bench reference: the Embree reference's speed on the default room from its
 * camera: milliseconds per image (median of --runs), rays per second, and the speed-up of
 * all cores over one thread measured in the same run. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "reference/reference.h"
#include "scene/scene.h"
#include "base/workpool.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median render time with `threads` threads; 0 or -1 with a message. */
static int measure(const scene *sc, const reference_render_desc *rd, int threads, int runs,
                   double *median_ms, double *rays)
{
    char err[512];
    reference *ref = reference_create(sc, threads, err, sizeof err);
    if (!ref) {
        fprintf(stderr, "bench reference: %s\n", err);
        return -1;
    }
    double ms[16];
    for (int i = 0; i < runs; i++) {
        reference_images img;
        if (reference_render(ref, rd, &img, err, sizeof err) != 0) {
            fprintf(stderr, "bench reference: %s\n", err);
            reference_destroy(ref);
            return -1;
        }
        ms[i] = img.render_ms;
        *rays = (double)img.rays;
        reference_images_free(&img);
    }
    reference_destroy(ref);
    qsort(ms, (size_t)runs, sizeof ms[0], cmp_double);
    *median_ms = runs % 2 ? ms[runs / 2] : 0.5 * (ms[runs / 2 - 1] + ms[runs / 2]);
    return 0;
}

int bench_reference(int argc, char **argv)
{
    int width = 160, height = 120, samples = 16, bounces = 8, runs = 3;
    const bench_option opts[] = {
        BENCH_INT("width", "W", "image width", &width, 1, 16384),
        BENCH_INT("height", "H", "image height", &height, 1, 16384),
        BENCH_INT("samples", "N", "paths per pixel", &samples, 1, 1 << 20),
        BENCH_INT("bounces", "B", "reflections per path", &bounces, 1, 1000),
        BENCH_INT("runs", "R", "timed runs (the median is printed)", &runs, 1, 16),
    };
    int pr = BENCH_PARSE("reference", "the Embree path tracer's speed", opts, argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    char err[512];
    scene sc;
    if (scene_load("default", &sc, err, sizeof err) != 0) {
        fprintf(stderr, "bench reference: %s\n", err);
        return 1;
    }
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, &sc);
    frame_view v;
    scene_camera cam;
    scene_default_camera(&sc, &cam);
    frame_view_scene_camera(&cam, cam.position, scene_far_plane(&sc), width, height, &v);
    reference_render_desc rd = {.params = &p, .view = &v, .samples = samples,
                                .max_bounces = bounces, .seed = 1};
    workpool *probe = workpool_create(0);
    int cores = probe ? workpool_threads(probe) : 1;
    workpool_destroy(probe);
    double ms_all, ms_one, rays;
    int rc = measure(&sc, &rd, 0, runs, &ms_all, &rays) || measure(&sc, &rd, 1, runs, &ms_one, &rays);
    if (rc == 0)
        printf("{\"bench\":\"reference\",\"width\":%d,\"height\":%d,\"samples\":%d,\"bounces\":%d,"
               "\"threads\":%d,\"ms\":%.1f,\"mrays_per_s\":%.2f,\"ms_1_thread\":%.1f,"
               "\"speedup\":%.2f,\"rays_per_path\":%.2f}\n",
               width, height, samples, bounces, cores, ms_all, rays / ms_all / 1e3, ms_one,
               ms_one / ms_all, rays / ((double)width * height * samples));
    scene_free(&sc);
    return rc ? 1 : 0;
}
#else
int bench_reference(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "bench reference: this build has no render node (cavelight_node)\n");
    return 1;
}
#endif
