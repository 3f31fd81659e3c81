/* pose_guard: sane poses pass untouched; NaN, absurd positions and non-rotations are
 * replaced by the last good pose (home before any); slightly sheared rotations are made
 * orthonormal; every event is counted by the rate limiter. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "base/vec3.h"
#include "pose_guard.h"

/* A 3 m cube CAVE's front wall and floor; home (0, 1.7, 0.5). */
static const char *config_json =
    "{\"master\": {\"bind\": \"tcp://127.0.0.1:1\", \"connect\": \"tcp://127.0.0.1:1\"},"
    " \"security\": {\"mode\": \"insecure\"}, \"observer\": {\"home\": [0, 1.7, 0.5]},"
    " \"screens\": [{\"name\": \"front\", \"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [1.5,0,-1.5], \"top_left\": [-1.5,3,-1.5]},"
    "  {\"name\": \"floor\", \"bottom_left\": [-1.5,0,1.5], \"bottom_right\": [1.5,0,1.5], \"top_left\": [-1.5,0,-1.5]}],"
    " \"nodes\": [{\"name\": \"n\", \"screens\": [\"front\"], \"resolution\": [8,8]}]}";

static const float I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

static void setup(pose_guard *g)
{
    static cluster_config cfg;
    char err[256];
    assert_int_equal(cluster_config_parse(config_json, strlen(config_json), "g.json", &cfg, err, sizeof err), 0);
    pose_guard_init(g, &cfg);
}

static input_pose pose(float x, float y, float z, const float r[9])
{
    input_pose p = {.valid = 1, .time = 1.0, .position = {x, y, z}};
    memcpy(p.rotation, r, sizeof p.rotation);
    return p;
}

static void test_space(void **state)
{
    (void)state;
    pose_guard g;
    setup(&g);
    /* Corners span 3 m on every axis: the space is grown by 3 m on every side. */
    const float lo[3] = {-4.5f, -3, -4.5f}, hi[3] = {4.5f, 6, 4.5f};
    for (int i = 0; i < 3; i++) {
        assert_float_equal(g.lo[i], lo[i], 1e-6);
        assert_float_equal(g.hi[i], hi[i], 1e-6);
    }
}

static void test_sane_kept_bad_replaced(void **state)
{
    (void)state;
    pose_guard g;
    setup(&g);
    /* A bad first pose: home, unrotated. */
    input_pose p = pose(NAN, 1, 0, I3);
    assert_int_equal(pose_guard_apply(&g, &g.head, &p, 0), POSE_GUARD_REPLACED);
    assert_float_equal(p.position[1], 1.7f, 0);
    assert_float_equal(p.position[2], 0.5f, 0);
    assert_memory_equal(p.rotation, I3, sizeof I3);
    /* A sane pose passes bit for bit, even on or behind a screen's plane (the node's job). */
    const float c = cosf(0.3f), s = sinf(0.3f);
    const float yaw[9] = {c, 0, -s, 0, 1, 0, s, 0, c};
    input_pose good = pose(0.2f, 1.6f, -1.6f, yaw), q = good;
    assert_int_equal(pose_guard_apply(&g, &g.head, &q, 0), POSE_GUARD_KEPT);
    assert_memory_equal(&q, &good, sizeof q);
    /* Each bad pose is the last good one instead. */
    const float mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1}, doubled[9] = {2, 0, 0, 0, 2, 0, 0, 0, 2};
    const float zero[9] = {0};
    input_pose bad[] = {pose(0, INFINITY, 0, I3), pose(120, 1.7f, 0, I3), pose(0, 1.7f, -4.6f, I3),
                        pose(0, 1.7f, 0, mirror), pose(0, 1.7f, 0, doubled), pose(0, 1.7f, 0, zero)};
    bad[0].rotation[4] = NAN;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(pose_guard_apply(&g, &g.head, &bad[i], 0), POSE_GUARD_REPLACED);
        assert_memory_equal(bad[i].position, good.position, sizeof good.position);
        assert_memory_equal(bad[i].rotation, good.rotation, sizeof good.rotation);
    }
    assert_int_equal(g.head.replaced, 7);
    /* The wand has its own last good pose and its own count. */
    assert_int_equal(g.wand.replaced, 0);
    input_pose w = pose(0, 0, 1e9f, I3);
    assert_int_equal(pose_guard_apply(&g, &g.wand, &w, 0), POSE_GUARD_REPLACED);
    assert_float_equal(w.position[2], 0.5f, 0);
    /* Not valid: not a pose yet, left alone. */
    input_pose none = {0};
    none.position[0] = NAN;
    assert_int_equal(pose_guard_apply(&g, &g.head, &none, 0), POSE_GUARD_KEPT);
}

static void test_sheared_rotation_repaired(void **state)
{
    (void)state;
    pose_guard g;
    setup(&g);
    /* Rounding noise far below POSE_GUARD_ROTATION_EXACT: kept as it is. */
    float r[9];
    memcpy(r, I3, sizeof r);
    r[3] = 1e-5f;
    input_pose p = pose(0, 1.7f, 0, r);
    assert_int_equal(pose_guard_apply(&g, &g.head, &p, 0), POSE_GUARD_KEPT);
    assert_memory_equal(p.rotation, r, sizeof r);
    /* A shear of 0.03 and a 2 % scale: repaired to the nearest orthonormal frame. */
    r[3] = 0.03f;
    r[8] = 1.02f;
    p = pose(0, 1.7f, 0, r);
    assert_int_equal(pose_guard_apply(&g, &g.head, &p, 0), POSE_GUARD_REPAIRED);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            assert_float_equal(vec3_dot(p.rotation + 3 * i, p.rotation + 3 * j), i == j, 1e-6);
    float z[3];
    vec3_cross(p.rotation, p.rotation + 3, z);
    assert_memory_equal(z, p.rotation + 6, sizeof z); /* right-handed */
    assert_true(p.rotation[0] > 0.999f && p.rotation[4] > 0.999f && p.rotation[8] > 0.999f);
    assert_int_equal(g.head.repaired, 1);
    /* The repaired pose is the new last good one. */
    input_pose bad = pose(NAN, 0, 0, I3);
    pose_guard_apply(&g, &g.head, &bad, 0);
    assert_memory_equal(bad.rotation, p.rotation, sizeof p.rotation);
}

/* A flood of bad poses is counted whole; the log prints a burst, then one line per
 * interval (ratelog.h). */
static void test_flood_rate_limited(void **state)
{
    (void)state;
    pose_guard g;
    setup(&g);
    for (int i = 0; i < 1000; i++) {
        input_pose p = pose(NAN, 0, 0, I3);
        pose_guard_apply(&g, &g.head, &p, 5.0 * i); /* 5 s at 200 Hz */
    }
    assert_int_equal(g.head.replaced, 1000);
    assert_int_equal(g.head.log.count, 1000);
    assert_true(g.head.log.skipped > 990);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_space),
        cmocka_unit_test(test_sane_kept_bad_replaced),
        cmocka_unit_test(test_sheared_rotation_repaired),
        cmocka_unit_test(test_flood_rate_limited),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
