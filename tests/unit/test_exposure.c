/* exposure: in a closed box every watt a light sends lands on a wall, so the walls' mean
 * irradiance is power / area exactly and their mean first-bounce radiance albedo * power /
 * (pi area): the exposure must put that at EXPOSURE_KEY. It follows the light and not the
 * units (a 10 times larger box with 100 times the intensity gets the same exposure),
 * counts emissive surfaces, and is 1 in a scene without light. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "frame/exposure.h"

static const double PI = 3.14159265358979323846;

/* A closed box of side (3, 2.5, 4) times k, grey walls of albedo 0.5 facing in. */
static void box_scene(scene *s, float k)
{
    memset(s, 0, sizeof *s);
    assert_true(scene_add_material(s, &(scene_material){.base_color = {0.5f, 0.5f, 0.5f, 1},
                                                        .base_color_texture = -1}) == 0);
    const float lo[3] = {0, 0, 0}, hi[3] = {3 * k, 2.5f * k, 4 * k};
    assert_int_equal(scene_add_box(s, lo, hi, 1, 0), 0);
    char err[128];
    assert_int_equal(scene_finish(s, err, sizeof err), 0);
}

static void point_light(frame_params *p, float k, float intensity)
{
    frame_params_default(p);
    p->light_count = 1;
    p->lights[0] = (frame_light){.enabled = 1, .type = SCENE_LIGHT_POINT, .position = {1.5f * k, 2 * k, 2 * k},
                                 .direction = {0, -1, 0}, .color = {1, 1, 1}, .intensity = intensity};
}

static void test_closed_box(void **state)
{
    (void)state;
    scene s;
    frame_params p;
    box_scene(&s, 1);
    point_light(&p, 1, 2);
    const double area = 2 * (3 * 2.5 + 3 * 4 + 2.5 * 4), radiance = 0.5 * 4 * PI * 2 / (PI * area);
    assert_float_equal(exposure_from_light(&p, &s), EXPOSURE_KEY / radiance, 1e-4);
    /* Twice the light: half the exposure. */
    p.lights[0].intensity = 4;
    assert_float_equal(exposure_from_light(&p, &s), EXPOSURE_KEY / (2 * radiance), 1e-4);
    /* Off: nothing emits, the default exposure. */
    p.lights[0].enabled = 0;
    assert_float_equal(exposure_from_light(&p, &s), 1.0f, 0);
    scene_free(&s);

    /* Ten times the size and a hundred times the intensity: the same irradiance. */
    box_scene(&s, 10);
    point_light(&p, 10, 200);
    assert_float_equal(exposure_from_light(&p, &s), EXPOSURE_KEY / radiance, 1e-3);
    scene_free(&s);
}

static void test_emitter(void **state)
{
    (void)state;
    scene s;
    box_scene(&s, 1);
    /* A 1 x 1 m panel of radiance 2 just inside the floor, facing up: pi 2 W. */
    assert_int_equal(scene_add_material(&s, &(scene_material){.base_color = {0.5f, 0.5f, 0.5f, 1},
                                                               .base_color_texture = -1,
                                                               .emissive = {2, 2, 2}}), 1);
    const float a[3] = {1, 0.01f, 1}, b[3] = {1, 0.01f, 2}, c[3] = {2, 0.01f, 2}, d[3] = {2, 0.01f, 1},
                up[3] = {0, 1, 0};
    assert_int_equal(scene_add_quad(&s, a, b, c, d, up, 1), 0);
    char err[128];
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    frame_params p;
    frame_params_default(&p);
    const double area = 2 * (3 * 2.5 + 3 * 4 + 2.5 * 4) + 1, radiance = 0.5 * PI * 2 / (PI * area);
    assert_float_equal(exposure_from_light(&p, &s), EXPOSURE_KEY / radiance, 1e-4);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_box),
        cmocka_unit_test(test_emitter),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
