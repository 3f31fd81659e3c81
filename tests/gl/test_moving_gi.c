/* GI follows moved objects: a renderer that saw the default room's tall box where it was
 * loaded and is then told it moved computes, in its next frame, exactly what a renderer
 * of a room whose file had the box there computes (the same checksum: ILPV's blockers
 * redone around the box on the CPU and the GL backend, with either transport, vpl's maps and shadow maps drawn
 * with the box where it is, ldm's layered depth maps drawn again, and so are the ldm AO's), and that differs from the frame with the box where it was
 * loaded. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "base/mat4.h"
#include "gl/gl_testutil.h"

static uint64_t first_frame(gltest *t, const scene *sc, const frame_params *f, const scene_pose *before,
                            const scene_pose *pose)
{
    char err[300];
    renderer_desc rd = {.gl = glctx_gl(t->ctx), .scene = sc, .first = f, .threads = 1};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r)
        fail_msg("%s", err);
    if (before) { /* a frame with the box at its first place: what a following node has seen */
        renderer_set_pose(r, before);
        renderer_frame_pass(r, f);
    }
    frame_params g = *f;
    g.reset_epoch++; /* the ILPV's light starts afresh: only the geometry can differ */
    renderer_set_pose(r, pose);
    renderer_frame_pass(r, &g);
    uint64_t sum = renderer_checksum_complete(r); /* with its GPU part (ldm's splits) */
    renderer_destroy(r);
    return sum;
}

enum { AO_W = 64, AO_H = 48 };

/* The ldm AO image of the first eye pass after the frame with the pose (first_frame()'s
 * order), gi none. */
static void first_ao(gltest *t, const scene *sc, const scene_pose *before, const scene_pose *pose,
                     float *out)
{
    char err[300];
    frame_params f = t->params;
    gltest_set(&f, "gi", "none");
    gltest_set(&f, "ao", "ldm");
    gltest_set(&f, "ao-directions", "32");
    gltest_set(&f, "ao-resolution", "64");
    renderer_desc rd = {.gl = glctx_gl(t->ctx), .scene = sc, .first = &f, .threads = 1};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r)
        fail_msg("%s", err);
    renderer_view v;
    const float eye[3] = {0.0f, 1.7f, 1.8f}, target[3] = {0.0f, 0.5f, -1.0f};
    gltest_look_at(&v, eye, target, 1.2f, AO_W, AO_H);
    renderer_image img;
    if (before) {
        renderer_set_pose(r, before);
        renderer_frame_pass(r, &f);
        assert_int_equal(renderer_eye_pass(r, &v, 1, &img), 0);
    }
    renderer_set_pose(r, pose);
    renderer_frame_pass(r, &f);
    assert_int_equal(renderer_eye_pass(r, &v, 1, &img), 0);
    assert_non_null(img.ao);
    memcpy(out, img.ao, AO_W * AO_H * 3 * sizeof *out);
    renderer_destroy(r);
}

static void test_moved_equals_built_there(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 1), 0);
    int box = scene_object_find(&t.scene, "tall_box");
    scene_pose rest, moved;
    scene_pose_rest(&t.scene, &rest);
    moved = rest;
    moved.offset[box][12] = -1.2f; /* 1.2 m towards the red wall, 0.3 m nearer */
    moved.offset[box][14] = 0.3f;
    /* The room as if its file had the box there: static triangles only. */
    static scene there;
    char err[300];
    assert_int_equal(scene_load("default", &there, err, sizeof err), 0);
    for (size_t k = 0; k < there.triangle_count; k++) {
        if (there.triangle_object[k] == box)
            for (int v = 0; v < 3; v++)
                mat4_transform_point(moved.offset[box], there.positions + 9 * k + 3 * v,
                                     there.positions + 9 * k + 3 * v);
        there.triangle_object[k] = -1;
    }
    there.object_count = 0;
    scene_pose none;
    scene_pose_rest(&there, &none);
    /* method, LPV backend, LPV transport */
    const char *methods[][3] = {{"ilpv", "cpu", "beams"}, {"ilpv", "gl", "beams"}, {"ilpv", "cpu", "paper"},
                                {"ilpv", "gl", "paper"}, {"vpl", NULL, NULL}, {"ldm", NULL, NULL}};
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++) {
        frame_params f = t.params;
        gltest_set(&f, "gi", methods[i][0]);
        if (methods[i][1]) {
            gltest_set(&f, "lpv", methods[i][1]);
            gltest_set(&f, "lpv-transport", methods[i][2]);
        }
        uint64_t followed = first_frame(&t, &t.scene, &f, &rest, &moved),
                 built = first_frame(&t, &there, &f, NULL, &none),
                 at_rest = first_frame(&t, &t.scene, &f, NULL, &rest);
        printf("%s %s %s: moved %016llx, built there %016llx, at rest %016llx\n", methods[i][0],
               methods[i][1] ? methods[i][1] : "", methods[i][2] ? methods[i][2] : "",
               (unsigned long long)followed, (unsigned long long)built, (unsigned long long)at_rest);
        assert_true(followed == built);
        assert_true(followed != at_rest);
    }
    /* The ldm AO's maps are drawn again too. */
    static float ao[3][AO_W * AO_H * 3];
    first_ao(&t, &t.scene, &rest, &moved, ao[0]);
    first_ao(&t, &there, NULL, &none, ao[1]);
    first_ao(&t, &t.scene, NULL, &rest, ao[2]);
    assert_memory_equal(ao[0], ao[1], sizeof ao[0]);
    assert_memory_not_equal(ao[0], ao[2], sizeof ao[0]);
    scene_free(&there);
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_moved_equals_built_there),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
