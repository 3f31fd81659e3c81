/* scene objects and poses: names kept from glTF (unique, printable, "nodeN" when unnamed),
 * parents' motion carried to children, visibility inherited, the file's animations
 * (linear rotation, STEP translation) by the clock, placement by scene_transform, and the
 * objects as parameter-store keys. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "base/mat4.h"
#include "cluster/scene_keys.h"
#include "gi/gi_settings.h"
#include "scene/scene_load.h"
#include "scene/scene_pose.h"

#define TURNTABLE CAVELIGHT_SOURCE_DIR "/scenes/turntable.gltf"

static float models[SCENE_MAX_OBJECTS][16];
static uint8_t shown[SCENE_MAX_OBJECTS];

static void load(const char *path, const scene_transform *t, scene *s)
{
    char err[512];
    scene_load_desc d = {.transform = t};
    if (scene_load_with(path, &d, s, err, sizeof err) != 0)
        fail_msg("%s", err);
}

static void near3(const float *got, float x, float y, float z)
{
    if (fabsf(got[0] - x) > 1e-4f || fabsf(got[1] - y) > 1e-4f || fabsf(got[2] - z) > 1e-4f)
        fail_msg("(%g, %g, %g), want (%g, %g, %g)", got[0], got[1], got[2], x, y, z);
}

static void test_builders_name_objects_uniquely(void **state)
{
    (void)state;
    scene s;
    memset(&s, 0, sizeof s);
    assert_int_equal(scene_begin_object(&s, "door", -1), 0);
    assert_int_equal(scene_begin_object(&s, "door", 0), 1);
    assert_int_equal(scene_begin_object(&s, "a b\tc\x01", 7), 2); /* parent 7 does not exist yet */
    assert_int_equal(scene_begin_object(&s, NULL, -1), 3);
    assert_string_equal(s.objects[1].name, "door#2");
    assert_int_equal(s.objects[1].parent, 0);
    assert_string_equal(s.objects[2].name, "a_b_c_");
    assert_int_equal(s.objects[2].parent, -1);
    assert_string_equal(s.objects[3].name, "object3");
    char longname[200];
    memset(longname, 'L', sizeof longname - 1);
    longname[sizeof longname - 1] = 0;
    int k = scene_begin_object(&s, longname, -1);
    assert_true(strlen(s.objects[k].name) < SCENE_NAME_MAX - 4);
    while (s.object_count < SCENE_MAX_OBJECTS)
        assert_true(scene_begin_object(&s, "x", -1) >= 0);
    assert_int_equal(scene_begin_object(&s, "one too many", -1), -1);
    scene_free(&s);
}

static void test_default_room_has_its_boxes(void **state)
{
    (void)state;
    scene s;
    load("default", NULL, &s);
    assert_int_equal(s.object_count, 2);
    int tall = scene_object_find(&s, "tall_box"), low = scene_object_find(&s, "low_box");
    assert_true(tall >= 0 && low >= 0);
    size_t counts[2] = {0}, fixed = 0;
    for (size_t t = 0; t < s.triangle_count; t++) {
        int o = s.triangle_object[t];
        if (o < 0)
            fixed++;
        else
            counts[o]++;
    }
    assert_int_equal(counts[tall], 12);
    assert_int_equal(counts[low], 12);
    assert_int_equal(fixed, s.triangle_count - 24);
    scene_free(&s);
}

static void test_parents_carry_children_and_hide_them(void **state)
{
    (void)state;
    scene s;
    load(TURNTABLE, NULL, &s);
    int table = scene_object_find(&s, "turntable"), statue = scene_object_find(&s, "statue");
    assert_true(table >= 0 && statue >= 0);
    assert_int_equal(s.objects[statue].parent, table);
    scene_pose p;
    scene_pose_rest(&s, &p);
    float up[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.5f, 0, 1};
    memcpy(p.offset[table], up, sizeof up);
    scene_pose_models(&s, &p, models, shown);
    near3(models[statue] + 12, 0, 0.5f, 0);
    scene_pose base;
    scene_pose_rest(&s, &base);
    assert_true(scene_pose_object_changed(&s, &p, &base, statue)); /* through its parent */
    assert_false(scene_pose_object_changed(&s, &p, &base, scene_object_find(&s, "lift")));
    p.visible[table] = 0;
    scene_pose_models(&s, &p, models, shown);
    assert_int_equal(shown[statue], 0);
    assert_int_equal(shown[scene_object_find(&s, "room")], 1);
    scene_free(&s);
}

static void test_animations_by_the_clock(void **state)
{
    (void)state;
    scene s;
    load(TURNTABLE, NULL, &s);
    assert_int_equal(s.anim_channel_count, 2);
    assert_true(s.anim_duration == 8.0f);
    int statue = scene_object_find(&s, "statue"), lift = scene_object_find(&s, "lift");
    scene_pose p;
    scene_pose_rest(&s, &p);
    /* A quarter turn at 2 s about the table's axis (-0.8, y, -1): c - R c. */
    assert_int_equal(scene_pose_animate(&s, 2.0, &p), 2);
    scene_pose_models(&s, &p, models, shown);
    near3(models[statue] + 12, 0.2f, 0, -1.8f);
    near3(models[lift] + 12, 0, 0.6f, 0);
    /* Halfway between keys: slerp gives 45 degrees; STEP holds the last key. */
    scene_pose_animate(&s, 1.0, &p);
    scene_pose_models(&s, &p, models, shown);
    assert_true(fabsf(models[statue][0] - sqrtf(0.5f)) < 1e-5f);
    near3(models[lift] + 12, 0, 0, 0);
    scene_pose_animate(&s, 3.999, &p);
    scene_pose_models(&s, &p, models, shown);
    near3(models[lift] + 12, 0, 0.6f, 0);
    /* The clock loops over the longest channel: 10 s is 2 s. */
    float at2[16];
    scene_pose_animate(&s, 2.0, &p);
    scene_pose_models(&s, &p, models, shown);
    memcpy(at2, models[statue], sizeof at2);
    scene_pose_animate(&s, 10.0, &p);
    scene_pose_models(&s, &p, models, shown);
    for (int i = 0; i < 16; i++)
        assert_true(fabsf(models[statue][i] - at2[i]) < 1e-4f);
    scene_free(&s);
}

/* A scene placed by scene_transform moves as the file says, in the CAVE's space: the
 * statue's model takes its placed rest position where the placed animation puts it. */
static void test_animations_follow_the_placement(void **state)
{
    (void)state;
    scene plain, placed;
    load(TURNTABLE, NULL, &plain);
    scene_transform t = {.scale = 2.0f, .rotation_deg = {0, 90, 0}, .translation = {1, 0, 3},
                         .anchor = SCENE_ANCHOR_NONE};
    load(TURNTABLE, &t, &placed);
    assert_int_equal(placed.placed, 1);
    int statue = scene_object_find(&plain, "statue");
    scene_pose a, b;
    scene_pose_rest(&plain, &a);
    scene_pose_rest(&placed, &b);
    scene_pose_animate(&plain, 3.0, &a);
    scene_pose_animate(&placed, 3.0, &b);
    float ma[SCENE_MAX_OBJECTS][16];
    scene_pose_models(&plain, &a, ma, shown);
    scene_pose_models(&placed, &b, models, shown);
    /* A vertex of the statue: animated then placed equals placed then animated. */
    size_t tri = 0;
    while (plain.triangle_object[tri] != statue)
        tri++;
    float moved[3], want[3], got[3];
    mat4_transform_point(ma[statue], plain.positions + 9 * tri, moved);
    mat4_transform_point(placed.placement, moved, want);
    mat4_transform_point(models[statue], placed.positions + 9 * tri, got);
    near3(got, want[0], want[1], want[2]);
    scene_free(&plain);
    scene_free(&placed);
}

static void test_objects_as_store_keys(void **state)
{
    (void)state;
    scene s;
    load(TURNTABLE, NULL, &s);
    static params_schema schema;
    static params_store m, n;
    static scene_keys keys;
    char err[300];
    gi_params_schema(&schema);
    int built_in = schema.count;
    assert_int_equal(scene_keys_add(&schema, &s, &keys, err, sizeof err), 0);
    assert_int_equal(schema.count, built_in + 2 * s.object_count);
    assert_true(params_schema_find(&schema, "object.statue") >= 0);
    assert_true(params_schema_find(&schema, "object.statue.visible") >= 0);
    params_init(&m, &schema);
    params_init(&n, &schema);
    scene_pose p, q;
    scene_pose_rest(&s, &p);
    scene_pose_rest(&s, &q);
    scene_keys_read(&m, &keys, &q); /* a fresh store: the scene as loaded */
    assert_memory_equal(&p, &q, sizeof p);
    scene_pose_animate(&s, 1.0, &p);
    p.visible[scene_object_find(&s, "lift")] = 0;
    scene_keys_write(&m, &keys, &p);
    assert_int_equal(params_changed_count(&m, 0), 2); /* the turntable's offset, the lift's flag */
    uint64_t v = params_commit(&m);
    static uint8_t buf[PARAMS_ENCODED_MAX];
    size_t len = params_encode_delta(&m, v - 1, buf, sizeof buf);
    assert_int_equal(len, (2 + 64) + (2 + 4));
    assert_int_equal(params_apply(&n, v, buf, len), 0);
    scene_keys_read(&n, &keys, &q);
    assert_memory_equal(&p, &q, sizeof p);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builders_name_objects_uniquely),
        cmocka_unit_test(test_default_room_has_its_boxes),
        cmocka_unit_test(test_parents_carry_children_and_hide_them),
        cmocka_unit_test(test_animations_by_the_clock),
        cmocka_unit_test(test_animations_follow_the_placement),
        cmocka_unit_test(test_objects_as_store_keys),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
