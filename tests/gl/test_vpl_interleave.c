/* Interleaved sampling of the vpl gather (node/vpl_interleave.h) on llvmpipe, default room,
 * 64 x 48, 256 VPLs: with 1 x 1 blocks the image is the plain gather's; with 4 x 4 blocks
 * two frames of a static scene are the same, and at depth edges (found by casting the
 * primary rays on the host) the blurred image keeps the step: its error there against the
 * plain image is well below that of a 4 x 4 box blur of the plain image. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "base/vec3.h"
#include "gl/gl_testutil.h"

enum { W = 64, H = 48, PIXELS = W * H * 3, K = 4 };

static renderer *make(gltest *t, int block)
{
    char err[512];
    renderer_desc rd = {.gl = glctx_gl(t->ctx), .scene = &t->scene, .rsm_size = 64,
                        .lpv_backend = RENDERER_LPV_CPU, .gi = FRAME_GI_VPL,
                        .vpl_interleave = block, .converge_threshold = -1};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r)
        fprintf(stderr, "%s\n", err);
    assert_non_null(r);
    return r;
}

static void render(gltest *t, renderer *r, float *indirect)
{
    frame_params p = t->params;
    p.gi = FRAME_GI_VPL;
    p.vpl_count = 256;
    renderer_frame_pass(r, &p);
    renderer_view v;
    const float eye[3] = {1.3f, 1.6f, 1.9f}, target[3] = {-0.5f, 0.9f, -1.2f};
    gltest_look_at(&v, eye, target, 1.15f, W, H);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(r, &v, 1, &img), 0);
    memcpy(indirect, img.indirect, sizeof(float) * PIXELS);
}

/* Distance from o along unit d to the nearest triangle of s (Moeller-Trumbore); INFINITY
 * when none. */
static float cast(const scene *s, const float o[3], const float d[3])
{
    float best = INFINITY;
    for (size_t j = 0; j < s->triangle_count; j++) {
        const float *p = s->positions + 9 * j;
        float e1[3], e2[3], q[3], t[3], h[3];
        for (int c = 0; c < 3; c++) {
            e1[c] = p[3 + c] - p[c];
            e2[c] = p[6 + c] - p[c];
            t[c] = o[c] - p[c];
        }
        h[0] = d[1] * e2[2] - d[2] * e2[1];
        h[1] = d[2] * e2[0] - d[0] * e2[2];
        h[2] = d[0] * e2[1] - d[1] * e2[0];
        float det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
        if (fabsf(det) < 1e-12f)
            continue;
        float u = (t[0] * h[0] + t[1] * h[1] + t[2] * h[2]) / det;
        q[0] = t[1] * e1[2] - t[2] * e1[1];
        q[1] = t[2] * e1[0] - t[0] * e1[2];
        q[2] = t[0] * e1[1] - t[1] * e1[0];
        float v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
        float dist = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
        if (u >= 0 && v >= 0 && u + v <= 1 && dist > 0 && dist < best)
            best = dist;
    }
    return best;
}

static float lum(const float *img, int x, int y)
{
    const float *c = img + 3 * (y * W + x);
    return c[0] + c[1] + c[2];
}

static void test_interleaved(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, RENDERER_LPV_CPU, 1), 0);
    static float plain[PIXELS], one[PIXELS], a[PIXELS], b[PIXELS];
    renderer *r = make(&t, 0);
    render(&t, r, plain);
    renderer_destroy(r);

    r = make(&t, 1); /* 1 x 1 blocks: the same sums, through the two passes */
    render(&t, r, one);
    renderer_destroy(r);
    double worst = 0, mean = 0;
    for (int i = 0; i < PIXELS; i++) {
        worst = fmax(worst, fabs((double)one[i] - plain[i]));
        mean += plain[i] / PIXELS;
    }
    printf("1 x 1 blocks: largest difference %.3g of a mean %.3g\n", worst, mean);
    assert_true(worst <= 1e-5 * mean);

    r = make(&t, K);
    render(&t, r, a);
    render(&t, r, b);
    assert_memory_equal(a, b, sizeof a); /* a static scene: the same frame */
    renderer_destroy(r);

    /* Depth edges: horizontal neighbours whose primary rays (cast here) meet surfaces more
     * than 20% apart in distance. At those pixels, the blurred image's error against the
     * plain one, and a K x K box blur's. */
    const float eye[3] = {1.3f, 1.6f, 1.9f}, target[3] = {-0.5f, 0.9f, -1.2f};
    float fw[3], rt[3], up[3], world_up[3] = {0, 1, 0};
    for (int c = 0; c < 3; c++)
        fw[c] = target[c] - eye[c];
    vec3_normalize(fw);
    vec3_cross(fw, world_up, rt);
    vec3_normalize(rt);
    vec3_cross(rt, fw, up);
    float th = tanf(1.15f / 2), aspect = (float)W / H;
    static float dist[W * H];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float sx = (2 * (x + 0.5f) / W - 1) * th * aspect, sy = (1 - 2 * (y + 0.5f) / H) * th;
            float d[3];
            for (int c = 0; c < 3; c++)
                d[c] = fw[c] + sx * rt[c] + sy * up[c];
            vec3_normalize(d);
            dist[y * W + x] = cast(&t.scene, eye, d);
        }
    double edge_err = 0, box_err = 0, all_err = 0;
    int edges = 0;
    for (int y = K; y < H - K; y++)
        for (int x = K; x < W - K; x++) {
            float p = lum(plain, x, y), dp = dist[y * W + x], dq = dist[y * W + x + 1];
            float box = 0;
            for (int j = 0; j < K; j++)
                for (int i = 0; i < K; i++)
                    box += lum(plain, x + i - K / 2, y + j - K / 2) / (K * K);
            all_err += fabs(lum(a, x, y) - p);
            if (!(fabsf(dp - dq) > 0.2f * fminf(dp, dq)))
                continue;
            edges++;
            edge_err += fabs(lum(a, x, y) - p);
            box_err += fabs(box - p);
        }
    all_err /= (double)(W - 2 * K) * (H - 2 * K);
    printf("%d x %d blocks: mean |error| %.3g (all), %.3g at %d edge pixels, where a box blur's "
           "is %.3g\n", K, K, all_err, edge_err / edges, edges, box_err / edges);
    assert_true(edges > 10);
    assert_true(edge_err < 0.5 * box_err);
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_interleaved),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
