/* light_view: a point light's six cube faces give every direction to exactly one face's
 * VPL region, with the margin around it inside the face's image; a directional light's
 * orthographic view holds the whole scene; the lights' powers are their closed forms. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "frame/light_view.h"

static const double PI = 3.14159265358979323846;

static void box_scene(scene *s)
{
    memset(s, 0, sizeof *s);
    assert_true(scene_add_material(s, &(scene_material){.base_color = {1, 1, 1, 1},
                                                        .base_color_texture = -1}) == 0);
    const float lo[3] = {-1, 0, -3}, hi[3] = {2, 2.5f, 1};
    assert_int_equal(scene_add_box(s, lo, hi, 1, 0), 0);
    char err[128];
    assert_int_equal(scene_finish(s, err, sizeof err), 0);
}

static void clip(const float m[16], const float p[3], float c[4])
{
    for (int r = 0; r < 4; r++)
        c[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

static void test_cube_faces(void **state)
{
    (void)state;
    scene s;
    box_scene(&s);
    frame_params p;
    frame_params_default(&p);
    p.light_count = 1;
    p.lights[0] = (frame_light){.enabled = 1, .type = SCENE_LIGHT_POINT, .position = {0.3f, 1.1f, -0.7f},
                                .direction = {0, -1, 0}, .color = {1, 1, 1}, .intensity = 2};
    light_view v[LIGHT_VIEW_MAX];
    const int size = 64;
    assert_int_equal(light_views(&p, &s, size, v), 6);
    /* Directions on a fine spiral over the sphere: exactly one face's VPL region each. */
    for (int k = 0; k < 2000; k++) {
        double z = 1 - 2 * (k + 0.5) / 2000, rho = sqrt(1 - z * z), phi = k * 2.399963;
        float q[3] = {p.lights[0].position[0] + (float)(rho * cos(phi)),
                      p.lights[0].position[1] + (float)(rho * sin(phi)),
                      p.lights[0].position[2] + (float)z};
        int owners = 0;
        for (int f = 0; f < 6; f++) {
            float c[4];
            clip(v[f].view_projection, q, c);
            if (c[3] <= 0)
                continue;
            float x = c[0] / c[3] * v[f].tan_half_fov, y = c[1] / c[3] * v[f].tan_half_fov;
            owners += fabsf(x) <= v[f].vpl_tan && fabsf(y) <= v[f].vpl_tan;
        }
        assert_int_equal(owners, 1);
    }
    /* The face's image is its 90 degrees plus LIGHT_VIEW_CUBE_MARGIN texels a side. */
    double texel = 2.0 * v[0].tan_half_fov / size;
    assert_true(fabs(v[0].tan_half_fov - 1.0 - LIGHT_VIEW_CUBE_MARGIN * texel) < 1e-6);
    assert_true(fabs(light_power(&p.lights[0], &s) - 4 * PI * 2) < 1e-5);
    scene_free(&s);
}

static void test_directional_view_holds_the_scene(void **state)
{
    (void)state;
    scene s;
    box_scene(&s);
    float d[3] = {0.4f, -0.8f, 0.3f}, len = sqrtf(0.16f + 0.64f + 0.09f);
    for (int a = 0; a < 3; a++)
        d[a] /= len;
    light_view v;
    light_directional_view(&s, d, &v);
    assert_true(v.orthographic);
    for (int k = 0; k < 8; k++) {
        float q[3], c[4];
        for (int a = 0; a < 3; a++)
            q[a] = (k >> a) & 1 ? s.bounds_max[a] : s.bounds_min[a];
        clip(v.view_projection, q, c);
        assert_true(c[3] == 1.0f);
        for (int a = 0; a < 3; a++)
            assert_true(fabsf(c[a]) <= 1.0f + 1e-5f);
        /* Its travel through the medium: from the bounds' sphere, never negative. */
        assert_true(light_directional_travel(&s, d, q) >= 0);
    }
    /* The window's corner and edges span 2 extent[0] x 2 extent[1], perpendicular to d. */
    for (int e = 1; e < 3; e++) {
        float dot = 0, l2 = 0;
        for (int a = 0; a < 3; a++) {
            dot += v.window[e][a] * d[a];
            l2 += v.window[e][a] * v.window[e][a];
        }
        assert_true(fabsf(dot) < 1e-5f);
        assert_true(fabsf(sqrtf(l2) - 2 * v.extent[e - 1]) < 1e-5f);
    }
    frame_light l = {.enabled = 1, .type = SCENE_LIGHT_DIRECTIONAL, .color = {1, 1, 1},
                     .intensity = 3};
    memcpy(l.direction, d, sizeof d);
    assert_true(fabs(light_power(&l, &s) - 3 * 4.0 * v.extent[0] * v.extent[1]) < 1e-4);
    scene_free(&s);
}

static void test_spot_power_and_cone(void **state)
{
    (void)state;
    scene s;
    box_scene(&s);
    frame_light l = {.enabled = 1, .position = {0, 2, 0}, .direction = {0, -1, 0},
                     .color = {1, 0.5f, 0}, .intensity = 6, .outer_angle = 2.0f, .inner_angle = 3};
    float outer, inner;
    light_cone(&l, &outer, &inner);
    assert_true(outer == 1.45f && inner == 1.45f);
    assert_true(fabs(light_power(&l, &s) - 6 * 0.5 * 2 * PI * (1 - cos(1.45f))) < 1e-4);
    l.enabled = 0;
    assert_true(light_power(&l, &s) == 0 && !light_is_lit(&l));
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube_faces),
        cmocka_unit_test(test_directional_view_holds_the_scene),
        cmocka_unit_test(test_spot_power_and_cone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
