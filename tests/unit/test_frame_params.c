/* frame_params_sanitize(): valid parameters pass unchanged, every bad field is repaired
 * as the header says. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <limits.h>
#include <math.h>
#include <string.h>

#include "frame/frame_params.h"

static frame_params valid(void)
{
    frame_params p;
    frame_params_default(&p);
    p.light_count = 2;
    for (int i = 0; i < 2; i++) {
        frame_light *l = &p.lights[i];
        l->enabled = 1;
        l->position[0] = 1.0f + i;
        l->position[1] = 2.5f;
        l->direction[1] = -1.0f;
        l->color[0] = l->color[1] = l->color[2] = 0.9f;
        l->intensity = 12.0f;
        l->outer_angle = 0.5f;
        l->inner_angle = 0.4f;
    }
    return p;
}

static void test_valid_unchanged(void **state)
{
    (void)state;
    frame_params p = valid(), q = p;
    assert_int_equal(frame_params_sanitize(&q), 0);
    assert_memory_equal(&p, &q, sizeof p);
    frame_params d;
    frame_params_default(&d);
    q = d;
    assert_int_equal(frame_params_sanitize(&q), 0);
    assert_memory_equal(&d, &q, sizeof d);
}

static void test_bad_light_disabled(void **state)
{
    (void)state;
    for (int field = 0; field < 8; field++) {
        frame_params p = valid();
        frame_light *l = &p.lights[1];
        switch (field) {
        case 7: l->type = (scene_light_type)7; break;
        case 0: l->position[2] = NAN; break;
        case 1: l->direction[0] = INFINITY; break;
        case 2: memset(l->direction, 0, sizeof l->direction); break;
        case 3: l->color[1] = NAN; break;
        case 4: l->intensity = INFINITY; break;
        case 5: l->outer_angle = NAN; break;
        default: l->inner_angle = -INFINITY; break;
        }
        assert_int_equal(frame_params_sanitize(&p), 1);
        assert_int_equal(p.lights[1].enabled, 0);
        assert_int_equal(p.lights[0].enabled, 1);
    }
}

static void test_light_repaired(void **state)
{
    (void)state;
    frame_params p = valid();
    frame_light *l = &p.lights[0];
    l->direction[0] = 3.0f;
    l->direction[1] = -4.0f;
    l->color[2] = -1.0f;
    l->intensity = 1e30f;
    assert_int_equal(frame_params_sanitize(&p), 3);
    assert_true(l->enabled);
    assert_float_equal(l->direction[0], 0.6f, 1e-6);
    assert_float_equal(l->direction[1], -0.8f, 1e-6);
    assert_true(l->color[2] == 0.0f);
    assert_true(l->intensity == FRAME_MAX_INTENSITY);
    l->intensity = -2.0f;
    assert_int_equal(frame_params_sanitize(&p), 1);
    assert_true(l->intensity == 0.0f);
}

/* A point light shines every way: a missing direction becomes -y, the light stays on. A
 * directional light needs one. */
static void test_light_types(void **state)
{
    (void)state;
    frame_params p = valid();
    p.lights[0].type = SCENE_LIGHT_POINT;
    p.lights[1].type = SCENE_LIGHT_DIRECTIONAL;
    frame_params q = p;
    assert_int_equal(frame_params_sanitize(&q), 0);
    assert_memory_equal(&p, &q, sizeof p);
    memset(p.lights[0].direction, 0, sizeof p.lights[0].direction);
    memset(p.lights[1].direction, 0, sizeof p.lights[1].direction);
    assert_int_equal(frame_params_sanitize(&p), 2);
    assert_true(p.lights[0].enabled && p.lights[0].direction[1] == -1.0f);
    assert_false(p.lights[1].enabled);
}

/* The frame setting named name (frame_params.h's tables). */
static const setting *row(const char *name)
{
    int k = setting_find(frame_transport_settings, frame_transport_setting_count, name);
    if (k >= 0)
        return &frame_transport_settings[k];
    k = setting_find(frame_display_settings, frame_display_setting_count, name);
    assert_true(k >= 0);
    return &frame_display_settings[k];
}

static void test_globals_repaired(void **state)
{
    (void)state;
    frame_params d = valid(), p = d;
    p.head[5] = NAN;
    p.navigation[12] = INFINITY;
    p.time = NAN;
    p.light_count = 1000;
    p.lpv_steps = INT_MAX;
    p.lambda_incr = NAN;
    p.absorption = INFINITY;
    p.scattering = -1.0f;
    p.environment = (frame_environment)99;
    p.display_gamma = 0.0f;
    p.exposure = NAN;
    assert_int_equal(frame_params_sanitize(&p), 11);
    assert_memory_equal(p.head, d.head, sizeof p.head);
    assert_memory_equal(p.navigation, d.navigation, sizeof p.navigation);
    assert_true(p.time == 0.0);
    assert_int_equal(p.light_count, FRAME_MAX_LIGHTS);
    assert_int_equal(p.lpv_steps, (int)row("steps")->max);
    assert_true(p.lambda_incr == 0.8f); /* NaN: the default */
    assert_true(p.absorption == 1.0f && p.scattering == 0.0f);
    assert_int_equal(p.environment, FRAME_ENV_DIM);
    assert_true(p.display_gamma == 2.2f && p.exposure == 1.0f);

    p = d;
    p.light_count = -3;
    p.lpv_steps = -1;
    p.lambda_incr = 1.5f;
    p.exposure = 1e9f;
    assert_int_equal(frame_params_sanitize(&p), 4);
    assert_int_equal(p.light_count, 0);
    assert_int_equal(p.lpv_steps, 0);
    assert_true(p.lambda_incr == 0.999f);
    assert_true(p.exposure == (float)row("exposure")->max);
    p.lambda_incr = INFINITY;
    p.exposure = -INFINITY;
    assert_int_equal(frame_params_sanitize(&p), 2);
    assert_true(p.lambda_incr == 0.999f && p.exposure == 1.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_valid_unchanged),
        cmocka_unit_test(test_bad_light_disabled),
        cmocka_unit_test(test_light_repaired),
        cmocka_unit_test(test_light_types),
        cmocka_unit_test(test_globals_repaired),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
