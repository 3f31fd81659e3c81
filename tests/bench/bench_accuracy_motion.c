/* cavelight-bench accuracy move|path: the LPV while lights move.
 *
 *   move  The light sits at A until the lattice is steady, then jumps `--distance` metres
 *         (1.4 m as in the paper's Fig. 3.3) to B. Per frame after the jump: the summed
 *         absolute lattice difference to B's own steady state (relative), the same for the
 *         indirect image, and the display error against B's path-traced reference.
 *   path  The light circles its start at walking speed; per frame the change of the final,
 *         indirect and direct images from the frame before and the largest 8-bit jump of any
 *         pixel. The direct image's change is the motion itself, the rest is the LPV's. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"

enum { MAX_CONFIGS = 8 };

typedef struct motion_options {
    acc_options common;
    double lambdas[MAX_CONFIGS];
    int lambda_count, lattice, steps, frames, classic;
    float distance, speed, radius;
} motion_options;

/* A positive number from an option's text; 0 after one line on stderr. */
static float positive(const char *name, const char *option, const char *text)
{
    char *end;
    float v = strtof(text, &end);
    if (*end || !(v > 0))
        fprintf(stderr, "cavelight-bench accuracy %s: --%s %s: expected a positive number\n", name, option, text);
    return *end || !(v > 0) ? 0.0f : v;
}

/* 0, 1 after --help (exit 0), -1 after one line on stderr (exit 2). */
static int parse_motion(motion_options *m, int argc, char **argv, const char *name)
{
    *m = (motion_options){
        .common = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                   .ref_samples = 64},
        .lattice = 32, .steps = 8, .frames = 60, .classic = 1, .radius = 0.5f,
    };
    const char *lambda_text = "0,0.5,0.8,0.9", *distance_text = "1.4", *speed_text = "0.5";
    const bench_option opts[] = {
        ACC_COMMON_OPTIONS(&m->common),
        BENCH_TEXT("lambdas", "L,L,..", "lambda_incr values, each in [0, 1)", &lambda_text),
        BENCH_INT("lattice", "N", "cells along the longest axis", &m->lattice, 2, 512),
        BENCH_INT("steps", "S", "propagation steps per frame", &m->steps, 1, 1024),
        BENCH_INT("frames", "N", "frames after the move (move) or in all (path)", &m->frames, 2, 100000),
        BENCH_INT("classic", "0|1", "also the classic accumulating LPV", &m->classic, 0, 1),
        BENCH_TEXT("distance", "M", "move: how far the light jumps, metres", &distance_text),
        BENCH_TEXT("speed", "M/S", "path: the light's speed on its circle", &speed_text),
    };
    char bench[32];
    snprintf(bench, sizeof bench, "accuracy %s", name);
    int rc = BENCH_PARSE(bench, strcmp(name, "move") == 0
                             ? "error after an abrupt light move, per lambda_incr (scripts/chart.sh runs it)"
                             : "frame-to-frame change for a light moving smoothly (scripts/chart.sh runs it)",
                         opts, argc, argv);
    if (rc != 0)
        return rc;
    char *s = (char *)lambda_text, *end;
    int bad = 0;
    while (*s && m->lambda_count < MAX_CONFIGS && !bad) {
        double l = strtod(s, &end);
        bad = end == s || l < 0 || l >= 1 || (*end && *end != ',');
        m->lambdas[m->lambda_count++] = l;
        s = *end == ',' ? end + 1 : end;
    }
    if (bad || *s || m->lambda_count == 0) {
        fprintf(stderr, "cavelight-bench accuracy %s: --lambdas %s: expected 1..%d comma-separated numbers "
                "in [0, 1)\n", name, lambda_text, MAX_CONFIGS);
        return -1;
    }
    m->distance = positive(name, "distance", distance_text);
    m->speed = m->distance > 0 ? positive(name, "speed", speed_text) : 0;
    return m->speed > 0 ? 0 : -1;
}

/* B: the first light moved along the longer horizontal axis of the bounds, towards the
 * centre, so it stays inside the scene. */
static void moved_light(const acc_setup *s, const frame_params *a, float distance,
                        frame_params *b)
{
    *b = *a;
    int axis = s->sc.bounds_max[0] - s->sc.bounds_min[0] >=
                       s->sc.bounds_max[2] - s->sc.bounds_min[2] ? 0 : 2;
    float centre = 0.5f * (s->sc.bounds_min[axis] + s->sc.bounds_max[axis]);
    b->lights[0].position[axis] += a->lights[0].position[axis] > centre ? -distance : distance;
}

/* Configuration k: the lambdas in turn, then the classic LPV; on the CPU backend. Its
 * settings go into every frame of frames[0..n). */
static renderer *config_renderer(acc_setup *s, const motion_options *m, int k, int *classic,
                                 float *lambda, frame_params **frames, int n)
{
    *classic = k == m->lambda_count;
    *lambda = *classic ? 0.0f : (float)m->lambdas[k];
    acc_renderer_desc d = {.backend = ILPV_BACKEND_CPU, .lattice = m->lattice,
                           .classic = *classic};
    renderer *r = acc_renderer_create(s, &d, frames[0]);
    for (int i = 1; i < n; i++) {
        frames[i]->rsm_size = frames[0]->rsm_size;
        frames[i]->gi = frames[0]->gi;
        memcpy(frames[i]->gi_settings, frames[0]->gi_settings, sizeof frames[0]->gi_settings);
    }
    return r;
}

static double lattice_difference(const lpv_volume *a, const lpv_volume *b)
{
    double diff = 0, sum = 0;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++)
        for (size_t i = 0; i < a->cells; i++) {
            diff += fabs((double)a->ch[c][i] - (double)b->ch[c][i]);
            sum += fabs((double)b->ch[c][i]);
        }
    return sum > 0 ? diff / sum : 0;
}

static double mean_of(const float *v, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += v[i];
    return n ? sum / (double)n : 0;
}

int accuracy_move(int argc, char **argv)
{
    motion_options m;
    int parsed = parse_motion(&m, argc, argv, "move");
    if (parsed)
        return parsed > 0 ? 0 : 2;
    acc_setup s;
    if (acc_setup_open(&s, &m.common) != 0)
        return 1;
    frame_params a = s.base, b;
    moved_light(&s, &a, m.distance, &b);
    acc_reference ref;
    if (acc_reference_get(&s, &b, "moved", &ref) != 0) {
        acc_setup_close(&s);
        return 1;
    }
    size_t px = (size_t)m.common.width * m.common.height;
    float *steady_indirect = malloc(px * 3 * sizeof(float));
    uint8_t *steady_display = malloc(px * 3);
    FILE *csv = acc_open_csv(&s, "move",
        "config,lambda,frame,lattice_change,indirect_change,display_mae_steady,"
        "display_mae_reference");
    int rc = steady_indirect && steady_display && csv ? 0 : 1;
    printf("{\"bench\":\"accuracy\",\"experiment\":\"move\",\"scene\":\"%s\",\"distance\":%g,"
           "\"steps\":%d,\"lattice\":%d,\"configs\":[", m.common.scene, m.distance, m.steps,
           m.lattice);
    for (int k = 0; k < m.lambda_count + m.classic && rc == 0; k++) {
        int classic;
        float lambda;
        renderer *r = config_renderer(&s, &m, k, &classic, &lambda, (frame_params *[]){&a, &b}, 2);
        lpv_volume steady = {0};
        if (!r || lpv_volume_init(&steady, gi_ilpv_lattice(gi_ilpv_of(renderer_gi(r)))->n, LPV_LIGHT_CHANNELS)) {
            rc = 1;
            break;
        }
        a.lpv_steps = b.lpv_steps = m.steps;
        a.lambda_incr = b.lambda_incr = lambda;
        renderer_image img;
        /* B's own steady state: what the lattice converges to after the move. */
        b.reset_epoch = a.reset_epoch + 1;
        for (int f = 0; f < 2 * acc_warm_frames(lambda) + 2; f++)
            renderer_frame_pass(r, &b);
        lpv_volume_copy(&steady, gi_ilpv_volume(gi_ilpv_of(renderer_gi(r))));
        rc = renderer_eye_pass(r, &s.view, 1, &img);
        if (rc == 0) {
            memcpy(steady_indirect, img.indirect, px * 3 * sizeof(float));
            memcpy(steady_display, img.rgb, px * 3);
        }
        double steady_mean = mean_of(steady_indirect, px * 3);
        /* A until steady, then the jump. */
        a.reset_epoch = b.reset_epoch + 1;
        b.reset_epoch = a.reset_epoch;
        for (int f = 0; f < 2 * acc_warm_frames(lambda) + 2 && rc == 0; f++)
            renderer_frame_pass(r, &a);
        int settle = -1;
        for (int f = 1; f <= m.frames && rc == 0; f++) {
            renderer_frame_pass(r, &b);
            if ((rc = renderer_eye_pass(r, &s.view, 1, &img)) != 0)
                break;
            double lat = lattice_difference(gi_ilpv_volume(gi_ilpv_of(renderer_gi(r))), &steady);
            double ind = steady_mean > 0
                             ? acc_linear_mae(img.indirect, steady_indirect, px) / steady_mean : 0;
            if (settle < 0 && lat < 0.05)
                settle = f;
            fprintf(csv, "%s,%g,%d,%.6g,%.6g,%.5f,%.5f\n", classic ? "classic" : "incremental",
                    lambda, f, lat, ind, acc_display_mae(img.rgb, steady_display, px),
                    acc_display_mae(img.rgb, ref.display, px));
        }
        printf("%s{\"mode\":\"%s\",\"lambda\":%g,\"frames_to_5pct\":%d}", k ? "," : "",
               classic ? "classic" : "incremental", lambda, settle);
        lpv_volume_free(&steady);
        renderer_destroy(r);
    }
    printf("]}\n");
    if (csv)
        fclose(csv);
    free(steady_indirect);
    free(steady_display);
    acc_reference_free(&ref);
    acc_setup_close(&s);
    return rc ? 1 : 0;
}

int accuracy_path(int argc, char **argv)
{
    motion_options m;
    int parsed = parse_motion(&m, argc, argv, "path");
    if (parsed)
        return parsed > 0 ? 0 : 2;
    m.common.ref_samples = 1; /* no reference needed */
    acc_setup s;
    if (acc_setup_open(&s, &m.common) != 0)
        return 1;
    size_t px = (size_t)m.common.width * m.common.height;
    float *prev[3] = {malloc(px * 3 * sizeof(float)), malloc(px * 3 * sizeof(float)),
                      malloc(px * 3 * sizeof(float))};
    uint8_t *prev_rgb = malloc(px * 3);
    FILE *csv = acc_open_csv(&s, "path",
        "config,lambda,frame,change_final,change_indirect,change_direct,max_jump");
    int rc = prev[0] && prev[1] && prev[2] && prev_rgb && csv ? 0 : 1;
    printf("{\"bench\":\"accuracy\",\"experiment\":\"path\",\"scene\":\"%s\",\"speed\":%g,"
           "\"radius\":%g,\"steps\":%d,\"lattice\":%d,\"configs\":[", m.common.scene, m.speed,
           m.radius, m.steps, m.lattice);
    const float *start = s.base.lights[0].position;
    for (int k = 0; k < m.lambda_count + m.classic && rc == 0; k++) {
        int classic;
        float lambda;
        frame_params fp = s.base;
        renderer *r = config_renderer(&s, &m, k, &classic, &lambda, (frame_params *[]){&fp}, 1);
        if (!r) {
            rc = 1;
            break;
        }
        fp.lpv_steps = m.steps;
        fp.lambda_incr = lambda;
        fp.reset_epoch = (uint32_t)k + 1;
        double worst_indirect = 0, worst_final = 0, worst_direct = 0;
        int worst_jump = 0;
        int warm = acc_warm_frames(lambda);
        for (int f = -warm; f <= m.frames && rc == 0; f++) {
            /* Circle around the start, radius m.radius, at m.speed m/s, 60 frames a second. */
            double angle = f > 0 ? f * m.speed / (m.radius * 60.0) : 0;
            fp.lights[0].position[0] = start[0] + m.radius * (float)(cos(angle) - 1.0);
            fp.lights[0].position[2] = start[2] + m.radius * (float)sin(angle);
            renderer_frame_pass(r, &fp);
            if (f < 0)
                continue;
            renderer_image img;
            if ((rc = renderer_eye_pass(r, &s.view, 1, &img)) != 0)
                break;
            const float *now[3] = {img.final, img.indirect, img.direct};
            if (f > 0) {
                double change[3];
                for (int i = 0; i < 3; i++) {
                    double mean = mean_of(now[i], px * 3);
                    change[i] = mean > 0 ? acc_linear_mae(now[i], prev[i], px) / mean : 0;
                }
                int jump = 0;
                for (size_t i = 0; i < px * 3; i++) {
                    int dj = abs((int)img.rgb[i] - (int)prev_rgb[i]);
                    jump = dj > jump ? dj : jump;
                }
                fprintf(csv, "%s,%g,%d,%.6g,%.6g,%.6g,%d\n", classic ? "classic" : "incremental",
                        lambda, f, change[0], change[1], change[2], jump);
                worst_final = fmax(worst_final, change[0]);
                worst_indirect = fmax(worst_indirect, change[1]);
                worst_direct = fmax(worst_direct, change[2]);
                worst_jump = jump > worst_jump ? jump : worst_jump;
            }
            for (int i = 0; i < 3; i++)
                memcpy(prev[i], now[i], px * 3 * sizeof(float));
            memcpy(prev_rgb, img.rgb, px * 3);
        }
        printf("%s{\"mode\":\"%s\",\"lambda\":%g,\"max_change_final\":%.5f,"
               "\"max_change_indirect\":%.5f,\"max_change_direct\":%.5f,\"max_jump\":%d}",
               k ? "," : "", classic ? "classic" : "incremental", lambda, worst_final,
               worst_indirect, worst_direct, worst_jump);
        renderer_destroy(r);
    }
    printf("]}\n");
    if (csv)
        fclose(csv);
    for (int i = 0; i < 3; i++)
        free(prev[i]);
    free(prev_rgb);
    acc_setup_close(&s);
    return rc ? 1 : 0;
}
#else
typedef int accuracy_motion_unused;
#endif
