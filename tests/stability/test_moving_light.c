/* A spot moving at walking speed (0.5 m/s at 60 Hz: 8.3 mm a frame) across the default
 * room for 60 frames, 160x120: the picture must change smoothly. Measured per frame pair:
 * mean |difference| of the linear final images over their mean, and the largest jump of
 * any 8-bit channel of the tone-mapped image. Baseline: the same light standing still
 * (after the same warm-up), and the incremental history lambda 0 vs 0.8. The light moves
 * every frame, so a future "skip propagation once converged" cannot make this vacuous.
 *
 * Measured (build/stability_moving_light), lattice 20, RSM 64, 30 warm-up frames:
 *   static light, lambda 0.8:  frame-to-frame mean |diff| / mean 0 (the renderer skips converged
 *                              frames; 2e-8 when it computes them after 30 frames), 8-bit jump 0
 *   0.5 m/s, lambda 0:         0.0044, jump 22 (at the spot's cone edge and shadows)
 *   0.5 m/s, lambda 0.8:       0.0042, jump 21
 *   lambda 0.8, last moving frame vs the light converged where it stopped: 1.7e-4 (the
 *   history trails little: blocking and the open lattice faces remove most of a frame's
 *   light within its 8 steps, so the history decays much faster than lambda^k; the
 *   figure was 1.7e-5 before the indirect level followed the injected energy, which made
 *   the indirect light, and so its trail, several times brighter).
 * The jumps above 12 are one pixel on the first moving frame: the low box's top corner,
 * whose front face lies in the plane of the spot (lit at exactly 90 degrees), where one
 * RSM texel of the box's edge changes hands; with the former constant depth bias (which
 * let zero-thickness walls leak, test_leaks.c) it measured 9.
 * A renderer that dropped its history every other frame measured 0.045 and failed.
 * With the ballistic transport and the ILPV's chains (ilpv.h), lattice 20, RSM 64:
 *   0.5 m/s, lambda 0:         0.00638, jump 34 (one pixel at the spot's cone edge)
 *   0.5 m/s, lambda 0.8:       0.00603, jump 29
 *   lambda 0.8, last moving frame vs converged where it stopped: 0.0137 (the far field
 *   stays as it was when the light started to move until the light stops: the indirect
 *   light now reaches the far walls at its physical level, so its trail shows; it fades as
 *   lambda^k once the light stops). Showing the whole last picture instead of its far part
 *   measured 0.0415 (a jump when the light starts to move) and trailing 0.066.
 * Bounds: static 1e-8 and jump <= 1; moving 0.0075 and jump <= 40 for both lambdas and
 * at least 100 x the static figure; trailing 0.02. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "stability_util.h"

enum { W = 160, H = 120, WARMUP = 30, FRAMES = 60 };

typedef struct smoothness {
    double mad;      /* largest mean |final_k - final_k-1| / mean final */
    int jump;        /* largest 8-bit jump of one channel of one pixel */
    float *last;     /* last linear final image (malloc'ed) */
} smoothness;

/* start: metres the light starts further along its path */
static smoothness run(stab_gl *g, const scene *s, float lambda, float speed, float start)
{
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, s);
    p.lambda_incr = lambda;
    p.reset_epoch++; /* each run starts from an empty history */
    renderer_view v;
    stab_view(&v, s->camera.position, s->camera.target, s->camera.yfov, W, H, 0.05f, 50.0f);
    size_t n = (size_t)W * H * 3;
    float *prev = malloc(n * sizeof *prev);
    uint8_t *prev_rgb = malloc(n);
    smoothness out = {0};
    out.last = malloc(n * sizeof *out.last);
    assert_true(prev && prev_rgb && out.last);
    const float x0 = p.lights[0].position[0] - start, step = speed / 60.0f;
    for (int f = 0; f < WARMUP + FRAMES; f++) {
        int moving = f - WARMUP;
        /* along -x, towards the red wall, keeping the spot's direction */
        p.lights[0].position[0] = x0 - step * (float)(moving > 0 ? moving : 0);
        p.time = f / 60.0;
        stab_frame_pass(g, &p);
        renderer_image img;
        assert_int_equal(renderer_eye_pass(g->r, &v, 1, &img), 0);
        assert_int_equal(stab_image_nonfinite(&img), 0);
        if (moving > 0) {
            double d = 0, m = 0;
            for (size_t i = 0; i < n; i++) {
                d += fabs((double)img.final[i] - prev[i]);
                m += img.final[i];
                int j = abs((int)img.rgb[i] - (int)prev_rgb[i]);
                out.jump = j > out.jump ? j : out.jump;
            }
            out.mad = fmax(out.mad, d / m);
        }
        memcpy(prev, img.final, n * sizeof *prev);
        memcpy(prev_rgb, img.rgb, n);
    }
    memcpy(out.last, prev, n * sizeof *prev);
    free(prev);
    free(prev_rgb);
    return out;
}

static void test_walking_speed_is_smooth(void **state)
{
    (void)state;
    scene s;
    char err[256];
    assert_int_equal(scene_load("default", &s, err, sizeof err), 0);
    stab_gl g;
    assert_int_equal(stab_open(&g, &s, 20), 0);
    const float travel = 0.5f * (FRAMES - 1) / 60.0f;
    smoothness still = run(&g, &s, 0.8f, 0.0f, 0.0f);
    smoothness l0 = run(&g, &s, 0.0f, 0.5f, 0.0f);
    smoothness l8 = run(&g, &s, 0.8f, 0.5f, 0.0f);
    /* How far the incremental light trails: the moving light's last frame against the
     * same light converged where it stopped. */
    smoothness end = run(&g, &s, 0.8f, 0.0f, travel);
    size_t n = (size_t)W * H * 3;
    double d = 0, m = 0;
    for (size_t i = 0; i < n; i++) {
        d += fabs((double)l8.last[i] - end.last[i]);
        m += end.last[i];
    }
    double lag = d / m;
    printf("static light, lambda 0.8: largest frame-to-frame mean |diff| / mean %.3g, "
           "largest 8-bit jump %d\n", still.mad, still.jump);
    printf("0.5 m/s, lambda 0:        %.3g, %d\n", l0.mad, l0.jump);
    printf("0.5 m/s, lambda 0.8:      %.3g, %d; last frame vs converged there: %.3g\n",
           l8.mad, l8.jump, lag);
    assert_true(still.mad <= 1e-8 && still.jump <= 1);
    assert_true(l0.mad > 100 * still.mad && l8.mad > 100 * still.mad); /* it did move */
    assert_true(l0.mad <= 0.0075 && l8.mad <= 0.0075);
    assert_true(l0.jump <= 40 && l8.jump <= 40);
    assert_true(lag <= 0.02);
    free(end.last);
    free(still.last);
    free(l0.last);
    free(l8.last);
    stab_close(&g);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_walking_speed_is_smooth),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
