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
 * With --gi caches the stages are importance, sat_select, proxy, occlusion (the frame pass)
 * and interpolate (the eye pass's interpolation), and the same frames run again with every
 * RSM texel as a VAL (caches-selection all, plain LightSkin): every_texel_gi_ms and the
 * speed-up of the selection, gi_ms against it.
 * With --gi ldm the stages are construct (the maps, rebuilt every frame here as a moving
 * scene would need them), photons and trace (the split), and splat_ms the eye pass's
 * splat; memory_mb the maps'. With --ao ldm|ssao, ao_ms is the eye pass's ambient
 * occlusion, ao_build_ms and ao_memory_mb its maps' (built once). A method's figures in ms
 * are medians over the frames like the passes. With --aa fxaa, aa_ms is the eye pass's
 * anti-aliasing.
 * GPU passes use the
 * renderer's timer queries (read late, never stalling), the rest host clocks. The first
 * two frames are warm-up and not counted. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "frame/frame_params.h"
#include "gl/glctx.h"
#include "present/present.h"
#include "frame/frame_view.h"
#include "frame/offaxis.h"
#include "renderer.h"
#include "scene/scene.h"
#include "gi/gi_settings.h"

enum { WARMUP = 2, PASSES = 8, GI_STAGES = GI_STATS_MAX };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* 1 for a method's figure that is a per-frame time (its name ends in _ms). */
static int timed(const char *name)
{
    size_t n = strlen(name);
    return n > 3 && strcmp(name + n - 3, "_ms") == 0;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}


/* "gpu_ms": each stage's median over the measured frames whose timer queries arrived
 * (gpu_timer.h: a frame or more late, never waited for), stages in the last one's order. */
static void print_gpu_ms(const gpu_timer_result *res, int n)
{
    const gpu_timer_result *names = &res[n - 1];
    double *v = calloc((size_t)n, sizeof *v);
    printf(",\"gpu_ms\":{");
    for (int k = 0; k < names->count && v; k++) {
        int m = 0;
        for (int f = 0; f < n; f++)
            for (int i = 0; i < res[f].count; i++)
                if (strcmp(res[f].stage[i].name, names->stage[k].name) == 0)
                    v[m++] = res[f].stage[i].ms;
        printf("%s\"%s\":%.3f", k ? "," : "", names->stage[k].name, m ? median(v, m) : 0.0);
    }
    printf("}");
    free(v);
}

int bench_frame(int argc, char **argv)
{
    const char *scene_arg = "default";
    int width = 320, height = 240, frames = 10, gl_index = GLCTX_EGL;
    static const char *const gl_names[] = {"egl", "osmesa", "glfw"};
    frame_params fp;
    frame_params_default(&fp);
    const bench_option opts[] = {
        BENCH_TEXT("scene", "NAME|FILE", "a built-in scene or a glTF file", &scene_arg),
        BENCH_INT("width", "W", "image width", &width, 1, 16384),
        BENCH_INT("height", "H", "image height", &height, 1, 16384),
        BENCH_INT("frames", "N", "frames (the first ones warm up)", &frames, WARMUP + 1, 1000000),
        BENCH_CHOICE("gl", "egl|osmesa|glfw", "GL context", &gl_index, gl_names),
        BENCH_SETTINGS(&fp),
    };
    int pr = BENCH_PARSE("frame", "frame and eye passes of the renderer", opts, argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    const char *why = gi_check(&fp);
    if (why) {
        fprintf(stderr, "bench frame: %s\n", why);
        return 2;
    }
    const char *gl_name = gl_names[gl_index];
    int vpl = fp.gi == gi_method_find("vpl");
    char err[512];
    const char *path = scene_arg;
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
    frame_params_lights_from_scene(&fp, &sc);
    /* Static frames: measure the work, never skip it. */
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = &sc, .first = &fp, .no_reuse = 1};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r) {
        fprintf(stderr, "bench frame: %s\n", err);
        present_destroy(out);
        scene_free(&sc);
        return 1;
    }
    renderer_view v;
    scene_camera cam;
    scene_default_camera(&sc, &cam);
    frame_view_scene_camera(&cam, cam.position, scene_far_plane(&sc), width, height, &v);

    int n = frames - WARMUP;
    double *s = calloc((size_t)n * (PASSES + 1 + GI_STAGES), sizeof *s);
    gi_stats stages = {0}; /* the method's stage names */
    if (!s) {
        fprintf(stderr, "bench frame: out of memory\n");
        return 1;
    }
    int rc = 0;
    double *assign = calloc((size_t)n * 3, sizeof *assign); /* mono, per eye, enclosed */
    double *figs = calloc((size_t)n * (GI_STATS_MAX + 2), sizeof *figs); /* and AO's, AA's */
    gpu_timer_result *gpu = calloc((size_t)n, sizeof *gpu);
    renderer_ao_stats ao = {0};
    size_t pairs[3] = {0, 0, 0};
    for (int f = 0; f < frames && rc == 0; f++) {
        renderer_frame_pass(r, &fp);
        renderer_image img;
        rc = renderer_eye_pass(r, &v, 0, &img);
        renderer_timings t;
        renderer_get_timings(r, &t);
        if (f < WARMUP)
            continue;
        assign[f - WARMUP] = gi_stats_value(&t.gi, "assign_ms", NULL);
        gpu[f - WARMUP] = t.gpu;
        pairs[0] = (size_t)gi_stats_value(&t.gi, "assignments", NULL);
        stages = t.gi;
        ao = t.ao;
        for (int k = 0; k < stages.figure_count; k++)
            figs[(size_t)k * n + (f - WARMUP)] = t.gi.figure[k].value;
        figs[(size_t)GI_STATS_MAX * n + (f - WARMUP)] = t.ao.eye_ms;
        figs[(size_t)(GI_STATS_MAX + 1) * n + (f - WARMUP)] = t.aa_ms;
        for (int k = 0; k < stages.stage_count && k < GI_STAGES; k++)
            s[(size_t)(PASSES + 1 + k) * n + (f - WARMUP)] = t.gi.stage[k].value;
        double vals[PASSES] = {t.rsm_ms, gi_stats_total_ms(&t.gi), t.gbuffer_ms, t.shade_ms,
                               t.final_ms, t.frame_host_ms, t.eye_host_ms, 0};
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
    for (int f = 0; f < frames && rc == 0 && vpl; f++) {
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
                    ms += gi_stats_value(&t.gi, "assign_ms", NULL);
                    count += (size_t)gi_stats_value(&t.gi, "assignments", NULL);
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
    direct_only.gi = gi_method_find("none");
    for (int f = 0; f < frames && rc == 0 && vpl; f++) {
        renderer_frame_pass(r, &direct_only);
        renderer_image img;
        rc = renderer_eye_pass(r, &v, 0, &img);
        renderer_timings t;
        renderer_get_timings(r, &t);
        if (f >= WARMUP)
            base[f - WARMUP] = t.eye_host_ms;
    }
    /* caches: the same frames with every RSM texel as a VAL (plain LightSkin). */
    char selection[32];
    gi_get_text(&fp, "caches-selection", selection, sizeof selection);
    int caches = fp.gi == gi_method_find("caches") && strcmp(selection, "importance") == 0;
    double *lightskin = calloc((size_t)n, sizeof *lightskin);
    frame_params every_texel = fp;
    gi_set(&every_texel, "caches-selection", "all");
    for (int f = 0; f < frames && rc == 0 && caches; f++) {
        renderer_frame_pass(r, &every_texel);
        renderer_image img;
        rc = renderer_eye_pass(r, &v, 0, &img);
        renderer_timings t;
        renderer_get_timings(r, &t);
        if (f >= WARMUP)
            lightskin[f - WARMUP] = gi_stats_total_ms(&t.gi);
    }
    static const char *passes[PASSES] = {"rsm_ms", "gi_ms", "gbuffer_ms", "shade_ms",
                                         "final_ms", "frame_host_ms", "eye_host_ms", NULL};
    double med[PASSES + 1 + GI_STAGES];
    for (int p = 0; p < PASSES + 1 + GI_STAGES; p++) {
        qsort(s + (size_t)p * n, (size_t)n, sizeof *s, cmp_double);
        med[p] = n % 2 ? s[(size_t)p * n + n / 2]
                       : 0.5 * (s[(size_t)p * n + n / 2 - 1] + s[(size_t)p * n + n / 2]);
    }
    if (rc == 0) {
        printf("{\"bench\":\"frame\",\"scene\":\"%s\",\"triangles\":%zu,\"gl\":\"%s\","
               "\"renderer\":\"%s\",\"gi\":\"%s\",\"width\":%d,\"height\":%d,\"frames\":%d",
               scene_arg, sc.triangle_count, glctx_describe(ctx), glctx_renderer(ctx),
               gi_method_at(fp.gi)->name, width, height, n);
        for (int i = 0; i < gi_option_count(); i++) { /* the settings of the frame's method */
            const gi_option *o = gi_option_at(i);
            char text[64];
            if (o->method < 0 || o->method == fp.gi)
                printf(",\"%s\":\"%s\"", o->row->name, gi_get_text(&fp, o->row->name, text, sizeof text));
        }
        double eye_work = 0; /* the method's own eye-side times (ldm: its splat) */
        for (int i = 0; i < stages.figure_count; i++) { /* what the method reports of itself */
            const char *name = stages.figure[i].name;
            if (!strcmp(name, "assign_ms") || !strcmp(name, "assignments"))
                continue;
            double value = timed(name) ? median(figs + (size_t)i * n, n) : stages.figure[i].value;
            eye_work += timed(name) ? value : 0.0;
            printf(",\"%s\":%.6g", name, value);
        }
        if (fp.ao != FRAME_AO_OFF)
            printf(",\"ao_ms\":%.3f,\"ao_build_ms\":%.3f,\"ao_memory_mb\":%.6g,\"ao_overflow\":%zu",
                   median(figs + (size_t)GI_STATS_MAX * n, n), ao.build_ms, ao.memory_mb,
                   ao.overflow);
        if (fp.aa != FRAME_AA_OFF)
            printf(",\"aa_ms\":%.3f", median(figs + (size_t)(GI_STATS_MAX + 1) * n, n));
        for (int p = 0; p < PASSES - 1; p++)
            printf(",\"%s\":%.3f", passes[p], med[p]);
        for (int k = 0; k < stages.stage_count && k < GI_STAGES; k++)
            printf(",\"%s_ms\":%.3f", stages.stage[k].name, med[PASSES + 1 + k]);
        print_gpu_ms(gpu, n);
        double am[3];
        for (int k = 0; k < 3; k++) {
            qsort(assign + (size_t)k * n, (size_t)n, sizeof *assign, cmp_double);
            am[k] = n % 2 ? assign[(size_t)k * n + n / 2]
                          : 0.5 * (assign[(size_t)k * n + n / 2 - 1] + assign[(size_t)k * n + n / 2]);
        }
        double total = med[5] + med[6], gather = med[6] - med[PASSES] - am[0];
        if (vpl)
            printf(",\"eye_direct_only_ms\":%.3f,\"assign_ms\":%.3f,\"gather_ms\":%.3f,"
                   "\"assignments\":%zu,\"stereo_assign_per_eye_ms\":%.3f,"
                   "\"stereo_assign_enclosed_ms\":%.3f,\"stereo_assignments_per_eye\":%zu,"
                   "\"stereo_assignments_enclosed\":%zu,\"enclosed_fewer\":%.3f",
                   med[PASSES], am[0], gather, pairs[0], am[1], am[2], pairs[1], pairs[2],
                   pairs[1] ? 1.0 - (double)pairs[2] / (double)pairs[1] : 0.0);
        if (caches) {
            qsort(lightskin, (size_t)n, sizeof *lightskin, cmp_double);
            double all = n % 2 ? lightskin[n / 2] : 0.5 * (lightskin[n / 2 - 1] + lightskin[n / 2]);
            printf(",\"every_texel_gi_ms\":%.3f,\"speedup\":%.3f", all, med[1] > 0 ? all / med[1] : 0.0);
        }
        /* The method's work: its frame-pass stages, and vpl's gather. */
        double work = med[1] + eye_work + (vpl ? am[0] + gather : 0.0);
        printf(",\"gi_share\":%.3f}\n", total > 0 ? work / total : 0.0);
    } else {
        fprintf(stderr, "bench frame: %s\n", renderer_last_error(r));
    }
    free(s);
    free(assign);
    free(lightskin);
    free(figs);
    free(gpu);
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
