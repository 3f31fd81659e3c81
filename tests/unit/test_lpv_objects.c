/* lpv_objects: blockers that follow moving objects equal, bit for bit, blockers built
 * fresh for the same pose, whatever the objects did before (moved far or near, hidden,
 * shown again, moved with a parent), and redo only the cells around what moved. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "base/clock.h"
#include "base/mat4.h"
#include "gi/ilpv/lpv_objects.h"
#include "scene/scene_load.h"
#include "scene/scene_pose.h"

#define TURNTABLE CAVELIGHT_SOURCE_DIR "/scenes/turntable.gltf"

typedef struct rig {
    scene s;
    lattice_desc lat;
    lpv_objects o;
    lpv_blockers b;
    scene_pose pose, last;
    float model[SCENE_MAX_OBJECTS][16];
    uint8_t shown[SCENE_MAX_OBJECTS];
} rig;

static void rig_init(rig *r, const char *path, int cells)
{
    char err[300];
    assert_int_equal(scene_load(path, &r->s, err, sizeof err), 0);
    lattice_fit_desc fit = {.max_axis_cells = cells, .margin_cells = -1.0f};
    memcpy(fit.bounds_min, r->s.bounds_min, sizeof fit.bounds_min);
    memcpy(fit.bounds_max, r->s.bounds_max, sizeof fit.bounds_max);
    assert_int_equal(lattice_fit(&fit, &r->lat, err, sizeof err), 0);
    assert_int_equal(lpv_blockers_init(&r->b, r->lat.n), 0);
    assert_int_equal(lpv_objects_init(&r->o, &r->b, &r->lat, &r->s), 0);
    scene_pose_rest(&r->s, &r->pose);
    r->last = r->pose;
}

static void rig_free(rig *r)
{
    lpv_objects_free(&r->o);
    lpv_blockers_free(&r->b);
    scene_free(&r->s);
}

/* The blockers of the current pose from nothing: every shown triangle where its model
 * puts it. */
static void fresh(rig *r, lpv_blockers *out)
{
    assert_int_equal(lpv_blockers_init(out, r->lat.n), 0);
    scene_pose_models(&r->s, &r->pose, r->model, r->shown);
    float *p = malloc(r->s.triangle_count * 9 * sizeof(float));
    size_t n = 0;
    for (size_t t = 0; t < r->s.triangle_count; t++) {
        int o = r->s.triangle_object[t];
        if (o >= 0 && !r->shown[o])
            continue;
        for (int v = 0; v < 3; v++, n++) {
            const float *src = r->s.positions + 9 * t + 3 * v;
            if (o >= 0)
                mat4_transform_point(r->model[o], src, p + 3 * n);
            else
                memcpy(p + 3 * n, src, 3 * sizeof(float));
        }
    }
    lpv_geometry_add_triangles(out, &r->lat, p, n, NULL, n / 3, NULL);
    free(p);
}

/* Applies the pose's changes incrementally; returns the cells redone. */
static size_t step(rig *r)
{
    uint8_t moved[SCENE_MAX_OBJECTS];
    for (int o = 0; o < r->s.object_count; o++)
        moved[o] = (uint8_t)scene_pose_object_changed(&r->s, &r->pose, &r->last, o);
    scene_pose_models(&r->s, &r->pose, r->model, r->shown);
    lpv_objects_stats st;
    lpv_objects_update(&r->o, &r->b, &r->lat, &r->s, (const float (*)[16])r->model, r->shown, moved, &st);
    r->last = r->pose;
    return st.cells_redone;
}

static void expect_fresh(rig *r, int i)
{
    lpv_blockers f;
    fresh(r, &f);
    size_t differ = 0;
    for (size_t c = 0; c < f.cells; c++)
        differ += f.mask[c] != r->b.mask[c];
    if (differ)
        fail_msg("step %d: %zu of %zu cells differ from a fresh build", i, differ, f.cells);
    lpv_blockers_free(&f);
}

static float rnd(unsigned *seed, float lo, float hi)
{
    *seed = *seed * 1103515245u + 12345u;
    return lo + (hi - lo) * (float)((*seed >> 8) & 0xffff) / 65535.0f;
}

static void test_default_room_moves_equal_fresh_builds(void **state)
{
    (void)state;
    static rig r;
    rig_init(&r, "default", 32);
    expect_fresh(&r, -1); /* as loaded */
    unsigned seed = 7;
    for (int i = 0; i < 40; i++) {
        int o = i % 2;
        float m[16];
        float t[3] = {rnd(&seed, -1.5f, 1.5f), rnd(&seed, -0.2f, 0.6f), rnd(&seed, -1.5f, 1.5f)};
        float deg[3] = {0, rnd(&seed, -180, 180), rnd(&seed, -20, 20)};
        mat4_from_trs_deg(t, deg, rnd(&seed, 0.7f, 1.3f), m);
        memcpy(r.pose.offset[o], m, sizeof m);
        r.pose.visible[o] = i % 7 != 3; /* hidden now and then, shown again next time */
        step(&r);
        expect_fresh(&r, i);
    }
    /* Back to where they were loaded: the scene's own blockers. */
    scene_pose_rest(&r.s, &r.pose);
    step(&r);
    expect_fresh(&r, 40);
    rig_free(&r);
}

static void test_children_follow_and_only_the_cells_near_them_are_redone(void **state)
{
    (void)state;
    static rig r;
    rig_init(&r, TURNTABLE, 32);
    size_t cells = lattice_cell_count(&r.lat), most = 0;
    double t0 = clock_now_ms();
    for (int i = 1; i <= 16; i++) { /* two turns of the table: the statue goes round too */
        scene_pose_animate(&r.s, i * 0.5, &r.pose);
        size_t redone = step(&r);
        most = redone > most ? redone : most;
        expect_fresh(&r, i);
    }
    double ms = (clock_now_ms() - t0) / 16;
    printf("turntable, %dx%dx%d lattice: at most %zu of %zu cells redone per move, %.3f ms a move with the "
           "check\n", r.lat.n[0], r.lat.n[1], r.lat.n[2], most, cells, ms);
    assert_true(most > 0);
    assert_true(most < cells / 4);
    /* Nothing moved: nothing redone. */
    assert_int_equal(step(&r), 0);
    rig_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_room_moves_equal_fresh_builds),
        cmocka_unit_test(test_children_follow_and_only_the_cells_near_them_are_redone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
