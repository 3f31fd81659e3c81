/* An application's points drawn into the G-buffer (renderer_desc.gbuffer_draw,
 * node/app_draw.c) are lit like the scene and hidden behind it: points lying on the floor
 * with half the floor's albedo and its normal show half the floor's light (direct,
 * shadowed, and the GI method's indirect light), points behind a wall change no pixel,
 * points in front of a box cover it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "app_draw.h"
#include "base/mat4.h"
#include "gl/gl_testutil.h"

enum { W = 160, H = 120, GRID = 12 };

typedef struct points {
    app_draw *draw;
    cavelight_vertex v[GRID * GRID];
    int count;
} points;

static void draw_points(void *user, const frame_view *view, const float vp[16], GLuint fbo, GLuint depth)
{
    points *p = user;
    cavelight_draw d = {.width = view->width, .height = view->height, .framebuffer = fbo, .depth_texture = depth};
    memcpy(d.view_projection, vp, sizeof d.view_projection);
    memcpy(d.eye_position, view->eye_position, sizeof d.eye_position);
    app_draw_geometry(p->draw, &d, 0, p->v, p->count, 1.0f);
}

/* The final linear image of the default room from its camera, with the points or without. */
static void render(gltest *t, const renderer_view *v, points *p, float *out)
{
    renderer_set_gbuffer_draw(t->r, p ? draw_points : NULL, p);
    t->params.reset_epoch++; /* both renders start the ILPV's light afresh */
    renderer_image img;
    for (int f = 0; f < 3; f++) { /* the ILPV's light builds up over frames alike in both */
        renderer_frame_pass(t->r, &t->params);
        assert_int_equal(renderer_eye_pass(t->r, v, 1, &img), 0);
    }
    memcpy(out, img.final, (size_t)W * H * 3 * sizeof(float));
}

static int pixel_of(const renderer_view *v, const float p[3])
{
    float px[2];
    gltest_project(v, p, px);
    int x = (int)px[0], y = (int)px[1];
    return x >= 0 && y >= 0 && x < W && y < H ? y * W + x : -1;
}

static void test_points_on_the_floor_are_lit_like_it(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 1), 0);
    char err[300];
    static points p;
    assert_non_null(p.draw = app_draw_create(glctx_gl(t.ctx), err, sizeof err));
    renderer_view v;
    gltest_look_at(&v, t.scene.camera.position, t.scene.camera.target, t.scene.camera.yfov, W, H);
    const float *floor = t.scene.materials[0].base_color; /* white: the floor's */
    for (int i = 0; i < GRID; i++)
        for (int k = 0; k < GRID; k++) {
            cavelight_vertex *q = &p.v[p.count++];
            *q = (cavelight_vertex){.position = {-1.8f + 3.6f * i / (GRID - 1), 0.001f, -1.8f + 3.6f * k / (GRID - 1)},
                                    .normal = {0, 1, 0}};
            for (int c = 0; c < 3; c++)
                q->color[c] = 0.5f * floor[c];
        }
    static float base[W * H * 3], with[W * H * 3];
    render(&t, &v, NULL, base);
    render(&t, &v, &p, with);
    int seen = 0, halved = 0, far = 0;
    for (int i = 0; i < p.count; i++) {
        int px = pixel_of(&v, p.v[i].position);
        if (px < 0 || base[3 * px + 1] < 1e-3f)
            continue;
        float ratio = with[3 * px + 1] / base[3 * px + 1];
        if (fabsf(ratio - 1.0f) < 1e-4f)
            continue; /* a box stands in front of it */
        seen++;
        halved += fabsf(ratio - 0.5f) < 0.05f;
        far += fabsf(ratio - 0.5f) > 0.15f; /* a point 1 mm up may cross a shadow's edge */
    }
    printf("%d floor points seen, %d of them with half the floor's light (within 10%%), %d beyond 30%%\n",
           seen, halved, far);
    assert_true(seen >= 20);
    assert_true(halved >= seen * 9 / 10);
    assert_int_equal(far, 0);
    app_draw_destroy(p.draw);
    gltest_close(&t);
}

static void test_points_hidden_behind_walls_and_covering_boxes(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 1), 0);
    char err[300];
    static points p;
    assert_non_null(p.draw = app_draw_create(glctx_gl(t.ctx), err, sizeof err));
    renderer_view v;
    gltest_look_at(&v, t.scene.camera.position, t.scene.camera.target, t.scene.camera.yfov, W, H);
    static float base[W * H * 3], with[W * H * 3];
    render(&t, &v, NULL, base);
    /* Behind the back wall (z = -2): drawn, never seen. */
    for (int i = 0; i < GRID * GRID; i++)
        p.v[i] = (cavelight_vertex){.position = {-1.5f + 3.0f * (i % GRID) / GRID, 0.3f + 2.4f * (i / GRID) / GRID, -2.3f},
                                    .color = {1, 0, 0}};
    p.count = GRID * GRID;
    render(&t, &v, &p, with);
    assert_memory_equal(base, with, sizeof base);
    /* In front of the tall box (x 0.5..1.2, z -1.4..-0.7): seen where they are. */
    for (int i = 0; i < GRID * GRID; i++)
        p.v[i].position[2] = -0.5f, p.v[i].position[0] = 0.55f + 0.6f * (i % GRID) / GRID,
        p.v[i].position[1] = 0.2f + 1.2f * (i / GRID) / GRID;
    render(&t, &v, &p, with);
    int changed = 0;
    for (int i = 0; i < p.count; i++) {
        int px = pixel_of(&v, p.v[i].position);
        changed += px >= 0 && fabsf(with[3 * px] - base[3 * px]) > 1e-3f;
    }
    printf("%d of %d points in front of the box seen\n", changed, p.count);
    assert_true(changed > p.count / 2);
    app_draw_destroy(p.draw);
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_points_on_the_floor_are_lit_like_it),
        cmocka_unit_test(test_points_hidden_behind_walls_and_covering_boxes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
