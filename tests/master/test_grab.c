/* The wand's grab layout (grab.h) on the default room: C picks the object the wand's ray
 * meets first (not one hidden, not one behind a wall or another object), the object
 * follows the wand while C is held (moves and turns), stays where it was let go, and a
 * child is carried through its parent's motion; R reaches the grab layout only when the
 * session has objects (interaction_desc.grab). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "base/mat4.h"
#include "grab.h"
#include "interaction.h"
#include "scene/scene_load.h"

static scene room;
static int tall, low;

static int setup(void **state)
{
    (void)state;
    char err[300];
    if (scene_load("default", &room, err, sizeof err) != 0)
        return -1;
    tall = scene_object_find(&room, "tall_box");
    low = scene_object_find(&room, "low_box");
    return tall < 0 || low < 0;
}

static int teardown(void **state)
{
    (void)state;
    scene_free(&room);
    return 0;
}

/* The wand at p pointing along -Z turned by yaw about +y. */
static void wand_at(input_state *in, float x, float y, float z, float yaw)
{
    in->wand.valid = 1;
    in->wand.position[0] = x;
    in->wand.position[1] = y;
    in->wand.position[2] = z;
    memset(in->wand.rotation, 0, sizeof in->wand.rotation);
    in->wand.rotation[0] = cosf(yaw);
    in->wand.rotation[2] = -sinf(yaw);
    in->wand.rotation[4] = 1;
    in->wand.rotation[6] = sinf(yaw);
    in->wand.rotation[8] = cosf(yaw);
}

static void test_pick_nearest_shown(void **state)
{
    (void)state;
    scene_pose p;
    scene_pose_rest(&room, &p);
    float d;
    /* Straight at the tall box's front (z = -0.7) from z 0.5. */
    assert_int_equal(grab_pick(&room, &p, (const float[3]){0.85f, 0.8f, 0.5f}, (const float[3]){0, 0, -1}, &d),
                     tall);
    assert_true(fabsf(d - 1.2f) < 1e-4f);
    /* At the low box, which stands in front of nothing movable. */
    assert_int_equal(grab_pick(&room, &p, (const float[3]){-0.3f, 0.3f, 1.5f}, (const float[3]){0, 0, -1}, NULL),
                     low);
    /* At a wall: nothing to pick. */
    assert_int_equal(grab_pick(&room, &p, (const float[3]){-1.5f, 1.0f, 0}, (const float[3]){0, 0, -1}, NULL), -1);
    /* Hidden: the ray goes on to the back wall. */
    p.visible[tall] = 0;
    assert_int_equal(grab_pick(&room, &p, (const float[3]){0.85f, 0.8f, 0.5f}, (const float[3]){0, 0, -1}, NULL),
                     -1);
    /* Moved: picked where it is now, not where it was loaded. */
    p.visible[tall] = 1;
    p.offset[tall][12] = -2.0f; /* x 0.5..1.2 -> -1.5..-0.8 */
    assert_int_equal(grab_pick(&room, &p, (const float[3]){0.85f, 0.8f, 0.5f}, (const float[3]){0, 0, -1}, NULL),
                     -1);
    assert_int_equal(grab_pick(&room, &p, (const float[3]){-1.15f, 0.8f, 0.5f}, (const float[3]){0, 0, -1}, NULL),
                     tall);
}

static void test_carry_turn_and_let_go(void **state)
{
    (void)state;
    scene_pose p;
    scene_pose_rest(&room, &p);
    frame_params f;
    frame_params_default(&f);
    grab g;
    grab_init(&g);
    input_state in;
    memset(&in, 0, sizeof in);
    wand_at(&in, 0.85f, 0.8f, 0.5f, 0);
    /* C held from another layout: no pick when the layout becomes grab. */
    in.buttons = 1u << INPUT_BUTTON_C;
    assert_int_equal(grab_update(&g, &room, &p, &f, &in, 1), 0);
    in.buttons = 0;
    grab_update(&g, &room, &p, &f, &in, 1);
    in.buttons = in.pressed = 1u << INPUT_BUTTON_C;
    assert_int_equal(grab_update(&g, &room, &p, &f, &in, 1), 1);
    assert_int_equal(g.object, tall);
    in.pressed = 0;
    /* Moved 0.3 m left and 0.2 m up: the box goes along. */
    wand_at(&in, 0.55f, 1.0f, 0.5f, 0);
    grab_update(&g, &room, &p, &f, &in, 1);
    assert_true(fabsf(p.offset[tall][12] + 0.3f) < 1e-5f && fabsf(p.offset[tall][13] - 0.2f) < 1e-5f);
    /* Turned a quarter about the wand's own position: the box swings round it. */
    wand_at(&in, 0.55f, 1.0f, 0.5f, (float)(3.14159265 / 2));
    grab_update(&g, &room, &p, &f, &in, 1);
    float corner[3], at[3] = {1.2f, 0.0f, -0.7f};
    mat4_transform_point(p.offset[tall], at, corner);
    /* The corner was (0.35, -0.8, -1.2) from the wand when picked; a quarter turn about +y
     * takes (x, z) to (z, -x): now (-1.2, -0.8, -0.35) from the wand. */
    assert_true(fabsf(corner[0] - (0.55f - 1.2f)) < 1e-4f);
    assert_true(fabsf(corner[1] - (1.0f - 0.8f)) < 1e-4f);
    assert_true(fabsf(corner[2] - (0.5f - 0.35f)) < 1e-4f);
    /* Let go: it stays; the wand moves on alone. */
    float kept[16];
    memcpy(kept, p.offset[tall], sizeof kept);
    in.buttons = 0;
    assert_int_equal(grab_update(&g, &room, &p, &f, &in, 1), 0);
    wand_at(&in, 0.0f, 1.0f, 0.5f, 0);
    grab_update(&g, &room, &p, &f, &in, 1);
    assert_memory_equal(p.offset[tall], kept, sizeof kept);
    /* In another layout C picks nothing. */
    in.buttons = in.pressed = 1u << INPUT_BUTTON_C;
    wand_at(&in, -0.3f, 0.3f, 1.5f, 0);
    assert_int_equal(grab_update(&g, &room, &p, &f, &in, 0), 0);
    assert_int_equal(g.object, -1);
}

static void test_grab_layout_only_with_objects(void **state)
{
    (void)state;
    input_state in;
    memset(&in, 0, sizeof in);
    frame_params f;
    frame_params_default(&f);
    for (int with = 0; with < 2; with++) {
        interaction ia;
        interaction_init(&ia, &(interaction_desc){.grab = with});
        int seen_grab = 0;
        for (int i = 0; i < 8; i++) {
            in.pressed = 1u << INPUT_BUTTON_R;
            interaction_update(&ia, &in, 0.01, &f);
            seen_grab |= ia.layout == INTERACTION_GRAB;
            assert_int_equal(f.hud_layout, (int)ia.layout);
        }
        assert_int_equal(seen_grab, with);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pick_nearest_shown),
        cmocka_unit_test(test_carry_turn_and_let_go),
        cmocka_unit_test(test_grab_layout_only_with_objects),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
