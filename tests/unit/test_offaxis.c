/* offaxis: Kooima's generalized perspective projection and the look-at camera. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "frame/frame_view.h"
#include "frame/offaxis.h"

static void project(const float view[16], const float proj[16], const float p[3], float ndc[3])
{
    float e[4], c[4];
    for (int r = 0; r < 4; r++)
        e[r] = view[r] * p[0] + view[4 + r] * p[1] + view[8 + r] * p[2] + view[12 + r];
    for (int r = 0; r < 4; r++)
        c[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2] + proj[12 + r] * e[3];
    for (int i = 0; i < 3; i++)
        ndc[i] = c[i] / c[3];
}

/* The four screen corners land on the four NDC corners, for any eye in front. */
static void check_corners(const offaxis_screen_desc *d)
{
    float view[16], proj[16], ndc[3], tr[3];
    assert_int_equal(offaxis_screen(d, view, proj), 0);
    for (int i = 0; i < 3; i++)
        tr[i] = d->bottom_right[i] + d->top_left[i] - d->bottom_left[i];
    const float *corner[4] = {d->bottom_left, d->bottom_right, d->top_left, tr};
    const float want[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    for (int k = 0; k < 4; k++) {
        project(view, proj, corner[k], ndc);
        assert_true(fabsf(ndc[0] - want[k][0]) < 1e-4f);
        assert_true(fabsf(ndc[1] - want[k][1]) < 1e-4f);
        assert_true(ndc[2] > -1.0f && ndc[2] < 1.0f);
    }
}

static void test_corners_front_wall(void **state)
{
    (void)state;
    offaxis_screen_desc d = {
        .bottom_left = {-1.5f, 0.0f, -1.5f}, .bottom_right = {1.5f, 0.0f, -1.5f},
        .top_left = {-1.5f, 3.0f, -1.5f}, .eye = {0.3f, 1.7f, 0.4f},
    };
    check_corners(&d);
}

static void test_corners_side_wall_off_centre_eye(void **state)
{
    (void)state;
    /* Left wall of a CAVE (x = -1.5), seen from a head near the right front corner. */
    offaxis_screen_desc d = {
        .bottom_left = {-1.5f, 0.0f, 1.5f}, .bottom_right = {-1.5f, 0.0f, -1.5f},
        .top_left = {-1.5f, 3.0f, 1.5f}, .eye = {1.2f, 1.1f, 1.3f},
        .near_plane = 0.1f, .far_plane = 50.0f,
    };
    check_corners(&d);
}

/* A centred screen gives the symmetric frustum of the look-at camera. */
static void test_centred_screen_matches_look_at(void **state)
{
    (void)state;
    offaxis_screen_desc d = {
        .bottom_left = {-1, -1, -2}, .bottom_right = {1, -1, -2}, .top_left = {-1, 1, -2},
        .eye = {0, 0, 0}, .near_plane = 0.1f, .far_plane = 20.0f,
    };
    float v1[16], p1[16], v2[16], p2[16];
    assert_int_equal(offaxis_screen(&d, v1, p1), 0);
    const float pos[3] = {0, 0, 0}, target[3] = {0, 0, -1};
    assert_int_equal(offaxis_look_at(pos, target, 2.0f * atanf(0.5f), 1.0f, 0.1f, 20.0f, v2, p2), 0);
    for (int i = 0; i < 16; i++) {
        assert_true(fabsf(v1[i] - v2[i]) < 1e-5f);
        assert_true(fabsf(p1[i] - p2[i]) < 1e-5f);
    }
}

static void test_look_at_centre_and_edges(void **state)
{
    (void)state;
    const float pos[3] = {1, 2, 3}, target[3] = {1, 2, -7};
    float v[16], p[16], ndc[3];
    assert_int_equal(offaxis_look_at(pos, target, 1.0f, 2.0f, 0.1f, 100.0f, v, p), 0);
    project(v, p, target, ndc);
    assert_true(fabsf(ndc[0]) < 1e-5f && fabsf(ndc[1]) < 1e-5f);
    /* A point at the top edge of the vertical field of view. */
    const float top[3] = {1, 2 + 10 * tanf(0.5f), -7};
    project(v, p, top, ndc);
    assert_true(fabsf(ndc[1] - 1.0f) < 1e-4f);
    /* Looking straight down still works (up switches axis). */
    const float below[3] = {1, -5, 3};
    assert_int_equal(offaxis_look_at(pos, below, 1.0f, 1.0f, 0.1f, 100.0f, v, p), 0);
    project(v, p, below, ndc);
    assert_true(fabsf(ndc[0]) < 1e-5f && fabsf(ndc[1]) < 1e-5f);
}

static void test_degenerate_inputs(void **state)
{
    (void)state;
    float v[16], p[16];
    offaxis_screen_desc in_plane = {
        .bottom_left = {-1, -1, -2}, .bottom_right = {1, -1, -2}, .top_left = {-1, 1, -2},
        .eye = {0.5f, 0.2f, -2},
    };
    assert_int_equal(offaxis_screen(&in_plane, v, p), -1);
    offaxis_screen_desc behind = in_plane;
    behind.eye[2] = -3; /* behind the screen: it faces +z */
    assert_int_equal(offaxis_screen(&behind, v, p), -1);
    offaxis_screen_desc collinear = {
        .bottom_left = {0, 0, 0}, .bottom_right = {1, 0, 0}, .top_left = {2, 0, 0}, .eye = {0, 0, 1},
    };
    assert_int_equal(offaxis_screen(&collinear, v, p), -1);
    const float same[3] = {1, 1, 1};
    assert_int_equal(offaxis_look_at(same, same, 1, 1, 0.1f, 10, v, p), -1);
}

/* An eye on, just before or behind the screen's plane is moved to the near plane in front
 * along the normal, keeping its position across the screen; the corners then project to
 * the viewport's corners as for any eye in front. */
static void test_eye_moved_in_front(void **state)
{
    (void)state;
    const float bl[3] = {-1, -1, -2}, br[3] = {1, -1, -2}, tl[3] = {-1, 1, -2};
    const float eyes[][3] = {{0.5f, 0.2f, -2}, {0.5f, 0.2f, -1.99f}, {0.5f, 0.2f, -3}, {0, 0, -2.0f + 1e-7f}};
    for (size_t i = 0; i < sizeof eyes / sizeof eyes[0]; i++) {
        float moved[3], d;
        assert_int_equal(offaxis_eye_in_front(bl, br, tl, eyes[i], FRAME_VIEW_NEAR_PLANE, moved, &d), 1);
        assert_true(fabsf(d - (eyes[i][2] + 2)) < 1e-6f);
        assert_true(moved[0] == eyes[i][0] && moved[1] == eyes[i][1]);
        assert_true(fabsf(moved[2] - (-2 + FRAME_VIEW_NEAR_PLANE)) < 1e-6f);
        frame_view fv;
        assert_int_equal(frame_view_screen(bl, br, tl, eyes[i], 100, 64, 64, &fv, &d), 1);
        assert_true(fv.eye_position[2] == moved[2]);
        float ndc[3];
        project(fv.view, fv.projection, bl, ndc);
        assert_true(fabsf(ndc[0] + 1) < 1e-3f && fabsf(ndc[1] + 1) < 1e-3f);
        project(fv.view, fv.projection, (const float[3]){1, 1, -2}, ndc);
        assert_true(fabsf(ndc[0] - 1) < 1e-3f && fabsf(ndc[1] - 1) < 1e-3f);
    }
    /* Far enough in front: untouched, and the same view as before. */
    const float ok[3] = {0.3f, 0.1f, 0};
    float same[3];
    assert_int_equal(offaxis_eye_in_front(bl, br, tl, ok, FRAME_VIEW_NEAR_PLANE, same, NULL), 0);
    assert_memory_equal(same, ok, sizeof ok);
    frame_view fv;
    assert_int_equal(frame_view_screen(bl, br, tl, ok, 100, 64, 64, &fv, NULL), 0);
    /* Not finite, or degenerate corners: refused, never a NaN view. */
    const float nan_eye[3] = {NAN, 0, 0};
    assert_int_equal(frame_view_screen(bl, br, tl, nan_eye, 100, 64, 64, &fv, NULL), -1);
    assert_int_equal(frame_view_screen(bl, br, bl, ok, 100, 64, 64, &fv, NULL), -1);
}

static void test_stereo_eyes(void **state)
{
    (void)state;
    const float head[3] = {0, 1.7f, 0}, right[3] = {1, 0, 0};
    float l[3], r[3];
    offaxis_stereo_eyes(head, right, 0.065f, l, r);
    assert_true(fabsf(r[0] - l[0] - 0.065f) < 1e-6f);
    assert_true(fabsf(0.5f * (l[0] + r[0]) - head[0]) < 1e-6f);
    assert_true(l[1] == head[1] && r[2] == head[2]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_corners_front_wall),
        cmocka_unit_test(test_corners_side_wall_off_centre_eye),
        cmocka_unit_test(test_centred_screen_matches_look_at),
        cmocka_unit_test(test_look_at_centre_and_edges),
        cmocka_unit_test(test_degenerate_inputs),
        cmocka_unit_test(test_stereo_eyes),
        cmocka_unit_test(test_eye_moved_in_front),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
