/* The wand HUD on llvmpipe: drawn where the wand's pose projects in both eyes of an
 * off-axis stereo screen, the active layout's indicator brighter than the inactive ones,
 * bars as long as their values, the spot's cone at the spot, and nothing at all when
 * hidden. Every comparison is between two eye passes of the same frame, HUD shown and
 * hidden, so the only difference is the HUD. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "renderer_hud.h"

enum { W = 200, H = 150 };

static const float HEAD[3] = {0.3f, 1.5f, 1.2f};

/* A 2 x 1.5 m screen 1 m in front of the head, looking into the room (-Z). */
static void screen_view(const float eye[3], renderer_view *v)
{
    offaxis_screen_desc sd = {.bottom_left = {-0.7f, 0.75f, 0.2f},
                              .bottom_right = {1.3f, 0.75f, 0.2f},
                              .top_left = {-0.7f, 2.25f, 0.2f},
                              .near_plane = 0.02f, .far_plane = 50.0f};
    memcpy(sd.eye, eye, sizeof sd.eye);
    assert_int_equal(offaxis_screen(&sd, v->view, v->projection), 0);
    memcpy(v->eye_position, eye, sizeof v->eye_position);
    v->width = W;
    v->height = H;
}

/* One frame of p into a copy. With lambda_incr 0 every frame's light is the same, so
 * two frames differ only in what p changed. */
static uint8_t *render(gltest *t, const frame_params *p, const renderer_view *v)
{
    renderer_frame_pass(t->r, p);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(t->r, v, 0, &img), 0);
    uint8_t *copy = malloc((size_t)W * H * 3);
    assert_non_null(copy);
    memcpy(copy, img.rgb, (size_t)W * H * 3);
    return copy;
}

static int changed(const uint8_t *a, const uint8_t *b, int x, int y)
{
    if (x < 0 || y < 0 || x >= W || y >= H)
        return 0;
    size_t i = ((size_t)y * W + x) * 3;
    return a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
}

static double luma(const uint8_t *img, int x, int y)
{
    const uint8_t *p = img + ((size_t)y * W + x) * 3;
    return (p[0] + p[1] + p[2]) / 3.0;
}

/* Pixels per metre at a world point, along the wand's x axis. */
static double pixels_per_metre(const renderer_view *v, const float p[3], const float axis[3])
{
    float q[3], a[2], b[2];
    for (int k = 0; k < 3; k++)
        q[k] = p[k] + 0.01f * axis[k];
    gltest_project(v, p, a);
    gltest_project(v, q, b);
    return hypot(b[0] - a[0], b[1] - a[1]) / 0.01;
}

typedef struct window_stats {
    int count;
    double cx, cy, mean_luma;
} window_stats;

/* HUD pixels (shown differs from hidden) in a square window around a world point. */
static window_stats hud_pixels(const renderer_view *v, const uint8_t *shown, const uint8_t *hidden,
                               const float centre[3], int half)
{
    float c[2];
    gltest_project(v, centre, c);
    window_stats s = {0};
    for (int y = (int)c[1] - half; y <= (int)c[1] + half; y++)
        for (int x = (int)c[0] - half; x <= (int)c[0] + half; x++)
            if (changed(shown, hidden, x, y)) {
                s.count++;
                s.cx += x + 0.5;
                s.cy += y + 0.5;
                s.mean_luma += luma(shown, x, y);
            }
    if (s.count) {
        s.cx /= s.count;
        s.cy /= s.count;
        s.mean_luma /= s.count;
    }
    return s;
}

/* Context, one frame pass, and the wand 0.42 m in front of the head. */
static void setup(gltest *t, frame_params *p)
{
    assert_int_equal(gltest_open(t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    *p = t->params;
    p->lpv_steps = 4;
    p->lambda_incr = 0;
    renderer_frame_pass(t->r, p);
    renderer_view head;
    screen_view(HEAD, &head);
    renderer_hud_wand_in_front(head.view, p->wand);
}

static void test_hidden_draws_nothing(void **state)
{
    (void)state;
    gltest t;
    frame_params p;
    setup(&t, &p);
    renderer_view v;
    screen_view(HEAD, &v);
    p.hud_layout = -1;
    uint8_t *before = render(&t, &p, &v);
    p.hud_layout = 0;
    uint8_t *shown = render(&t, &p, &v);
    p.hud_layout = -1;
    uint8_t *after = render(&t, &p, &v);
    int differing = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            differing += changed(before, shown, x, y);
    printf("HUD pixels %d of %d; hidden image after showing equals the one before: %s\n",
           differing, W * H, memcmp(before, after, (size_t)W * H * 3) ? "no" : "yes");
    assert_true(differing > 200);
    assert_memory_equal(before, after, (size_t)W * H * 3);
    free(before);
    free(shown);
    free(after);
    gltest_close(&t);
}

/* Depth-tested against the scene: the same panel just in front of the back wall (z = -2)
 * is seen, just behind it is hidden. */
static void test_occluded_by_scene(void **state)
{
    (void)state;
    gltest t;
    frame_params p;
    setup(&t, &p);
    renderer_view v;
    screen_view(HEAD, &v);
    const float panel_z = p.wand[14] - RENDERER_HUD_DISTANCE;
    const float target_z[2] = {-1.9f, -2.1f};
    int pixels[2];
    for (int k = 0; k < 2; k++) {
        frame_params q = p;
        q.wand[14] += target_z[k] - panel_z;
        q.hud_layout = -1;
        uint8_t *hidden = render(&t, &q, &v);
        q.hud_layout = 0;
        uint8_t *shown = render(&t, &q, &v);
        pixels[k] = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                pixels[k] += changed(shown, hidden, x, y);
        free(hidden);
        free(shown);
    }
    printf("panel at z = -1.9: %d HUD pixels; at z = -2.1 (behind the wall): %d\n", pixels[0],
           pixels[1]);
    assert_true(pixels[0] > 10); /* a 0.28 m panel 3 m away: about 9 px wide */
    assert_int_equal(pixels[1], 0);
    gltest_close(&t);
}

/* Stereo: each eye sees the panel where its own off-axis projection puts the wand's HUD;
 * the torus (symmetric) centroid pins it down to a pixel, and the two eyes disagree by
 * the disparity of a panel 0.42 m away. */
static void test_where_each_eye_projects(void **state)
{
    (void)state;
    gltest t;
    frame_params p;
    setup(&t, &p);
    hud h;
    hud_describe(&p, 20, &h);
    renderer_hud_places places;
    renderer_hud_layout(&h, &places);
    float eyes[2][3];
    const float right[3] = {1, 0, 0};
    offaxis_stereo_eyes(HEAD, right, 0.065f, eyes[0], eyes[1]);
    float torus_x[2];
    for (int e = 0; e < 2; e++) {
        renderer_view v;
        screen_view(eyes[e], &v);
        float spot[2];
        gltest_project(&v, p.lights[0].position, spot);
        assert_true(spot[1] < 0); /* the spot's own cone is out of this view */
        p.hud_layout = -1;
        uint8_t *hidden = render(&t, &p, &v);
        p.hud_layout = 2;
        uint8_t *shown = render(&t, &p, &v);
        /* Every HUD pixel inside the projected panel box (1 px of rasterisation slack). */
        float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
        for (int k = 0; k < 8; k++) {
            float q[2];
            gltest_project(&v, places.panel_corner[k], q);
            for (int a = 0; a < 2; a++) {
                lo[a] = fminf(lo[a], q[a]);
                hi[a] = fmaxf(hi[a], q[a]);
            }
        }
        int outside = 0, inside = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                if (changed(shown, hidden, x, y)) {
                    int in = x + 1 >= lo[0] && x <= hi[0] + 1 && y + 1 >= lo[1] && y <= hi[1] + 1;
                    inside += in;
                    outside += !in;
                }
        double ppm = pixels_per_metre(&v, places.indicator[2], places.bar_axis);
        window_stats s = hud_pixels(&v, shown, hidden, places.indicator[2], (int)(0.022 * ppm));
        float want[2];
        gltest_project(&v, places.indicator[2], want);
        printf("%s eye: %d HUD pixels in the panel box, %d outside; torus centroid (%.2f, %.2f), "
               "projected (%.2f, %.2f)\n", e ? "right" : "left", inside, outside, s.cx, s.cy,
               want[0], want[1]);
        assert_true(inside > 200);
        assert_int_equal(outside, 0);
        assert_true(s.count > 20);
        assert_true(fabs(s.cx - want[0]) < 1.0 && fabs(s.cy - want[1]) < 1.0);
        torus_x[e] = want[0];
        free(hidden);
        free(shown);
    }
    printf("disparity of the torus: %.1f px\n", torus_x[0] - torus_x[1]);
    assert_true(fabsf(torus_x[0] - torus_x[1]) > 5.0f);
    gltest_close(&t);
}

/* The active layout's indicator is white, the others grey. */
static void test_active_indicator_brighter(void **state)
{
    (void)state;
    gltest t;
    frame_params p;
    setup(&t, &p);
    hud h;
    hud_describe(&p, 20, &h);
    renderer_hud_places places;
    renderer_hud_layout(&h, &places);
    renderer_view v;
    screen_view(HEAD, &v);
    int half = (int)(0.017 * pixels_per_metre(&v, places.indicator[0], places.bar_axis));
    p.hud_layout = -1;
    uint8_t *hidden = render(&t, &p, &v);
    const int layouts[2] = {0, 2};
    for (int k = 0; k < 2; k++) {
        p.hud_layout = layouts[k];
        uint8_t *shown = render(&t, &p, &v);
        window_stats arrow = hud_pixels(&v, shown, hidden, places.indicator[0], half);
        window_stats torus = hud_pixels(&v, shown, hidden, places.indicator[2], half);
        printf("layout %d: arrow %d px, mean %.1f; torus %d px, mean %.1f\n", layouts[k],
               arrow.count, arrow.mean_luma, torus.count, torus.mean_luma);
        assert_true(arrow.count > 10 && torus.count > 10);
        const window_stats *on = k == 0 ? &arrow : &torus, *off = k == 0 ? &torus : &arrow;
        assert_true(on->mean_luma > 1.25 * off->mean_luma);
        free(shown);
    }
    free(hidden);
    gltest_close(&t);
}

/* Bar A (absorption): the bright part of the bar ends where start + value * length
 * projects, so it grows with the value. The dark track beyond it is not counted. */
static void test_bar_length_follows_value(void **state)
{
    (void)state;
    gltest t;
    frame_params p;
    setup(&t, &p);
    renderer_view v;
    screen_view(HEAD, &v);
    const float values[3] = {0.2f, 0.5f, 0.9f};
    double previous = -1;
    for (int k = 0; k < 3; k++) {
        p.absorption = values[k];
        hud h;
        hud_describe(&p, 20, &h);
        renderer_hud_places places;
        renderer_hud_layout(&h, &places);
        p.hud_layout = -1;
        uint8_t *hidden = render(&t, &p, &v);
        p.hud_layout = 0;
        uint8_t *shown = render(&t, &p, &v);
        float a[2], b[2], end_world[3], want_end[2];
        float *start = places.bar_start[0];
        for (int c = 0; c < 3; c++)
            end_world[c] = start[c] + RENDERER_HUD_BAR_LENGTH * places.bar_axis[c];
        gltest_project(&v, start, a);
        gltest_project(&v, end_world, b);
        for (int c = 0; c < 3; c++)
            end_world[c] = start[c] + values[k] * RENDERER_HUD_BAR_LENGTH * places.bar_axis[c];
        gltest_project(&v, end_world, want_end);
        /* Walk the bar's centre line in quarter pixels; the last bright HUD pixel ends it. */
        double full = hypot(b[0] - a[0], b[1] - a[1]), drawn = 0;
        for (double s = 0; s <= full + 4; s += 0.25) {
            double x = a[0] + (b[0] - a[0]) * s / full, y = a[1] + (b[1] - a[1]) * s / full;
            int px = (int)floor(x), py = (int)floor(y);
            if (changed(shown, hidden, px, py) && luma(shown, px, py) > 160)
                drawn = s;
        }
        double want = hypot(want_end[0] - a[0], want_end[1] - a[1]);
        printf("A = %.1f: bar drawn %.1f px, projected %.1f px (full scale %.1f px)\n",
               values[k], drawn, want, full);
        assert_true(fabs(drawn - want) < 1.5);
        assert_true(drawn > previous + 5);
        previous = drawn;
        free(hidden);
        free(shown);
    }
    gltest_close(&t);
}

/* The spot's cone sits at the spot: looking at the spot, with the wand behind the camera,
 * the only HUD pixels are around the spot's projection. */
static void test_cone_at_spot(void **state)
{
    (void)state;
    gltest t;
    frame_params p;
    setup(&t, &p);
    const frame_light *l = &p.lights[0];
    float eye[3] = {l->position[0], l->position[1] - 0.5f, l->position[2] + 0.6f}, mid[3];
    for (int k = 0; k < 3; k++)
        mid[k] = l->position[k] + 0.5f * RENDERER_HUD_LIGHT_MARKER * l->direction[k];
    renderer_view v;
    gltest_look_at(&v, eye, mid, 0.6f, W, H);
    memcpy(p.wand + 12, (const float[3]){eye[0], eye[1], eye[2] + 3.0f}, 3 * sizeof(float));
    p.hud_layout = -1;
    uint8_t *hidden = render(&t, &p, &v);
    p.hud_layout = 1;
    uint8_t *shown = render(&t, &p, &v);
    /* Bound the cone by its apex and the rim of its base. */
    float c[2], lo[2], hi[2];
    gltest_project(&v, l->position, c);
    lo[0] = hi[0] = c[0];
    lo[1] = hi[1] = c[1];
    float rim = RENDERER_HUD_LIGHT_MARKER * tanf(l->outer_angle);
    for (int s = 0; s < 64; s++) {
        float q[3], px[2], dx = cosf(s * 0.0982f), dy = sinf(s * 0.0982f);
        /* any two unit vectors spanning the base plane */
        float u[3] = {-l->direction[1], l->direction[0], 0};
        float n = sqrtf(u[0] * u[0] + u[1] * u[1]);
        u[0] /= n, u[1] /= n;
        float w[3] = {l->direction[1] * u[2] - l->direction[2] * u[1],
                      l->direction[2] * u[0] - l->direction[0] * u[2],
                      l->direction[0] * u[1] - l->direction[1] * u[0]};
        for (int k = 0; k < 3; k++)
            q[k] = l->position[k] + RENDERER_HUD_LIGHT_MARKER * l->direction[k] +
                   rim * (dx * u[k] + dy * w[k]);
        gltest_project(&v, q, px);
        for (int a = 0; a < 2; a++) {
            lo[a] = fminf(lo[a], px[a]);
            hi[a] = fmaxf(hi[a], px[a]);
        }
    }
    int inside = 0, outside = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (changed(shown, hidden, x, y)) {
                int in = x + 1 >= lo[0] && x <= hi[0] + 1 && y + 1 >= lo[1] && y <= hi[1] + 1;
                inside += in;
                outside += !in;
            }
    printf("spot cone: %d pixels in its projected box, %d outside\n", inside, outside);
    assert_true(inside > 30);
    assert_int_equal(outside, 0);
    free(hidden);
    free(shown);
    gltest_close(&t);
}

/* A point light's star and a directional light's arrow sit at light 0 too: every HUD pixel
 * lies in the projection of the marker's bounding box (a cube of the marker's size around
 * a point light; along a directional light, as wide as the arrow's head). */
static void test_markers_by_type(void **state)
{
    (void)state;
    gltest t;
    frame_params p;
    setup(&t, &p);
    frame_light *l = &p.lights[0];
    memcpy(l->direction, (const float[3]){0, -1, 0}, sizeof l->direction);
    float eye[3] = {l->position[0] + 0.1f, l->position[1] - 0.5f, l->position[2] + 0.6f};
    renderer_view v;
    gltest_look_at(&v, eye, l->position, 0.6f, W, H);
    memcpy(p.wand + 12, (const float[3]){eye[0], eye[1], eye[2] + 3.0f}, 3 * sizeof(float));
    const float len = RENDERER_HUD_LIGHT_MARKER;
    for (int type = SCENE_LIGHT_POINT; type <= SCENE_LIGHT_DIRECTIONAL; type++) {
        l->type = (scene_light_type)type;
        p.hud_layout = -1;
        uint8_t *hidden = render(&t, &p, &v);
        p.hud_layout = 1;
        uint8_t *shown = render(&t, &p, &v);
        float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
        for (int k = 0; k < 8; k++) { /* the corners of the marker's box */
            float q[3], px[2];
            for (int a = 0; a < 3; a++) {
                float side = (k >> a) & 1 ? 0.5f : -0.5f;
                q[a] = type == SCENE_LIGHT_POINT
                           ? l->position[a] + side * len
                           : l->position[a] + ((k & 1) ? len * l->direction[a] : 0.0f) +
                                 (a ? side * 0.3f * len : 0.0f);
            }
            if (type == SCENE_LIGHT_DIRECTIONAL) /* along -y: as wide across x as across z */
                q[0] = l->position[0] + ((k >> 1) & 1 ? 0.15f : -0.15f) * len;
            gltest_project(&v, q, px);
            for (int a = 0; a < 2; a++) {
                lo[a] = fminf(lo[a], px[a]);
                hi[a] = fmaxf(hi[a], px[a]);
            }
        }
        int inside = 0, outside = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                if (changed(shown, hidden, x, y)) {
                    int in = x + 1 >= lo[0] && x <= hi[0] + 1 && y + 1 >= lo[1] && y <= hi[1] + 1;
                    inside += in;
                    outside += !in;
                }
        printf("%s marker: %d pixels in its projected box, %d outside\n",
               type == SCENE_LIGHT_POINT ? "point light" : "directional light", inside, outside);
        assert_true(inside > 30);
        assert_int_equal(outside, 0);
        free(hidden);
        free(shown);
    }
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hidden_draws_nothing),
        cmocka_unit_test(test_occluded_by_scene),
        cmocka_unit_test(test_where_each_eye_projects),
        cmocka_unit_test(test_active_indicator_brighter),
        cmocka_unit_test(test_bar_length_follows_value),
        cmocka_unit_test(test_cone_at_spot),
        cmocka_unit_test(test_markers_by_type),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
