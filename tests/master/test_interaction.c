/* Interaction layouts: speed law, flying, turning, flashlight pose, hue/saturation,
 * settings, round-robin switching and change-only updates. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "gi/gi_settings.h"
#include "interaction.h"

#define PI_F 3.14159265f

static const float I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

static void test_frame_init(frame_params *p)
{
    memset(p, 0, sizeof *p);
    for (int i = 0; i < 16; i += 5)
        p->head[i] = p->wand[i] = p->navigation[i] = 1.0f;
    p->light_count = 1;
    p->lights[0] = (frame_light){.enabled = 1, .position = {0, 2, 0}, .direction = {0, -1, 0},
                                 .color = {1, 0, 0}, .intensity = 10, .outer_angle = 0.5f,
                                 .inner_angle = 0.4f};
    p->lpv_steps = 8;
    p->absorption = 0.1f;
    p->scattering = 0.2f;
    p->lambda_incr = 0.5f;
}

/* Head at (0, 1.7, 0), wand at wand_pos with rotation yaw about Y. */
static input_state state_at(const float wand_pos[3], float yaw)
{
    input_state s;
    memset(&s, 0, sizeof s);
    s.head = (input_pose){.valid = 1, .position = {0, 1.7f, 0}};
    memcpy(s.head.rotation, I3, sizeof I3);
    s.wand = (input_pose){.valid = 1};
    memcpy(s.wand.position, wand_pos, 3 * sizeof(float));
    float c = cosf(yaw), sn = sinf(yaw);
    const float r[9] = {c, 0, -sn, 0, 1, 0, sn, 0, c};
    memcpy(s.wand.rotation, r, sizeof r);
    return s;
}

static uint32_t press(interaction *ia, input_state *s, frame_params *p, input_button b)
{
    s->pressed = 1u << b;
    uint32_t c = interaction_update(ia, s, 0.0, p);
    s->pressed = 0;
    return c;
}

static void test_speed_law(void **state)
{
    interaction_desc d = {0};
    assert_float_equal(interaction_speed(&d, 0.4f), 1.4f, 1e-6);
    assert_float_equal(interaction_speed(&d, 0.2f), 1.4f * powf(0.5f, 2.5f), 1e-6);
    assert_float_equal(interaction_speed(&d, 0.2f), 0.24749f, 1e-5);
    assert_float_equal(interaction_speed(&d, 0.8f), 7.91960f, 1e-4);
    assert_float_equal(interaction_speed(&d, 0.0f), 0.0f, 0);
    /* capped at max_distance (1 m by default) */
    assert_float_equal(interaction_speed(&d, 5.0f), interaction_speed(&d, 1.0f), 0);
    d.max_distance = 2.0f;
    assert_float_equal(interaction_speed(&d, 2.0f), 1.4f * powf(5.0f, 2.5f), 1e-3);
}

static void test_fly_along_wand(void **state)
{
    interaction ia;
    interaction_init(&ia, &(interaction_desc){0});
    frame_params p;
    test_frame_init(&p);
    /* wand 0.4 m in front of the head horizontally, 0.5 m lower: the height must not count */
    input_state s = state_at((float[]){0, 1.2f, -0.4f}, 0.0f);
    s.buttons = 1u << INPUT_BUTTON_C;
    uint32_t c = interaction_update(&ia, &s, 0.5, &p);
    assert_true(c & INTERACTION_CHANGED_NAVIGATION);
    assert_float_equal(p.navigation[12], 0.0f, 1e-6);
    assert_float_equal(p.navigation[13], 0.0f, 1e-6);
    assert_float_equal(p.navigation[14], -0.7f, 1e-5); /* 1.4 m/s for 0.5 s along -Z */
    /* pointing 90 degrees left (along -X) at 0.2 m: 1.4 * 0.5^2.5 m/s */
    s = state_at((float[]){-0.2f, 1.2f, 0.0f}, PI_F / 2);
    s.buttons = 1u << INPUT_BUTTON_C;
    interaction_update(&ia, &s, 1.0, &p);
    assert_float_equal(p.navigation[12], -0.24749f, 1e-5);
    assert_float_equal(p.navigation[14], -0.7f, 1e-5);
    /* M resets the navigation */
    c = press(&ia, &s, &p, INPUT_BUTTON_M);
    assert_true(c & INTERACTION_CHANGED_NAVIGATION);
    for (int i = 0; i < 16; i++)
        assert_float_equal(p.navigation[i], (i % 5 == 0) ? 1.0f : 0.0f, 0);
    /* with the CAVE turned 90 degrees left in the world, flying "forward" goes along -X */
    float nav[16] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 5, 0, 0, 1};
    memcpy(p.navigation, nav, sizeof nav);
    s = state_at((float[]){0, 1.2f, -0.4f}, 0.0f);
    s.buttons = 1u << INPUT_BUTTON_C;
    interaction_update(&ia, &s, 1.0, &p);
    assert_float_equal(p.navigation[12], 5.0f - 1.4f, 1e-5);
    assert_float_equal(p.navigation[14], 0.0f, 1e-5);
}

static void test_turn_by_dragging(void **state)
{
    interaction ia;
    interaction_init(&ia, &(interaction_desc){0});
    frame_params p;
    test_frame_init(&p);
    input_state s = state_at((float[]){0.3f, 1.2f, -0.4f}, 0.2f);
    s.head.position[0] = 0.5f;
    s.head.position[2] = -0.25f;
    s.buttons = 1u << INPUT_BUTTON_L;
    /* the first update starts the drag and changes nothing */
    assert_int_equal(interaction_update(&ia, &s, 0.016, &p) & INTERACTION_CHANGED_NAVIGATION, 0);
    float yaw = 0.2f + PI_F / 2;
    input_state s2 = state_at((float[]){0.3f, 1.2f, -0.4f}, yaw);
    s2.head = s.head;
    s2.buttons = s.buttons;
    assert_true(interaction_update(&ia, &s2, 0.016, &p) & INTERACTION_CHANGED_NAVIGATION);
    /* a quarter turn left about the vertical through the head: -Z now maps to -X ... */
    float fwd[3] = {-p.navigation[8], -p.navigation[9], -p.navigation[10]};
    assert_float_equal(fwd[0], -1.0f, 1e-5);
    assert_float_equal(fwd[1], 0.0f, 1e-6);
    assert_float_equal(fwd[2], 0.0f, 1e-5);
    assert_float_equal(p.navigation[5], 1.0f, 1e-6);
    /* ... and the head's place in the world does not move */
    const float *h = s.head.position, *n = p.navigation;
    for (int r = 0; r < 3; r += 2) {
        float w = n[r] * h[0] + n[4 + r] * h[1] + n[8 + r] * h[2] + n[12 + r];
        assert_float_equal(w, h[r], 1e-5);
    }
    /* releasing L ends the drag; the next press starts from the new orientation */
    s2.buttons = 0;
    assert_int_equal(interaction_update(&ia, &s2, 0.016, &p) & INTERACTION_CHANGED_NAVIGATION, 0);
    float kept[16];
    memcpy(kept, p.navigation, sizeof kept);
    s2.buttons = 1u << INPUT_BUTTON_L;
    interaction_update(&ia, &s2, 0.016, &p);
    assert_memory_equal(kept, p.navigation, sizeof kept);
}

static void test_flashlight_pose(void **state)
{
    interaction ia;
    interaction_init(&ia, &(interaction_desc){.first_layout = INTERACTION_LIGHTING});
    frame_params p;
    test_frame_init(&p);
    /* CAVE turned 90 degrees left and moved to (10, 0, -3) in the world */
    float nav[16] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 10, 0, -3, 1};
    memcpy(p.navigation, nav, sizeof nav);
    input_state s = state_at((float[]){0.2f, 1.1f, -0.5f}, 0.0f);
    /* without C the light stays */
    assert_int_equal(interaction_update(&ia, &s, 0.016, &p) & INTERACTION_CHANGED_LIGHT, 0);
    s.buttons = 1u << INPUT_BUTTON_C;
    assert_true(interaction_update(&ia, &s, 0.016, &p) & INTERACTION_CHANGED_LIGHT);
    const frame_light *l = &p.lights[0];
    /* position: N * (0.2, 1.1, -0.5) = (10 - 0.5, 1.1, -3 - 0.2) */
    assert_float_equal(l->position[0], 9.5f, 1e-5);
    assert_float_equal(l->position[1], 1.1f, 1e-5);
    assert_float_equal(l->position[2], -3.2f, 1e-5);
    /* direction: the wand's -Z turned by N: -X */
    assert_float_equal(l->direction[0], -1.0f, 1e-6);
    assert_float_equal(l->direction[2], 0.0f, 1e-6);
    /* tilt the wand 45 degrees down: direction follows, stays unit length */
    float c = cosf(PI_F / 4), sn = sinf(PI_F / 4);
    const float pitch[9] = {1, 0, 0, 0, c, -sn, 0, sn, c}; /* -Z column -> (0, -sn, -c) */
    memcpy(s.wand.rotation, pitch, sizeof pitch);
    interaction_update(&ia, &s, 0.016, &p);
    assert_float_equal(l->direction[0], -c, 1e-6);
    assert_float_equal(l->direction[1], -sn, 1e-6);
    float len = sqrtf(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                      l->direction[2] * l->direction[2]);
    assert_float_equal(len, 1.0f, 1e-6);
    /* intensity: M up, L down, by sqrt(2) a press */
    s.buttons = 0;
    press(&ia, &s, &p, INPUT_BUTTON_M);
    press(&ia, &s, &p, INPUT_BUTTON_M);
    assert_float_equal(l->intensity, 20.0f, 1e-4);
    assert_true(press(&ia, &s, &p, INPUT_BUTTON_L) & INTERACTION_CHANGED_LIGHT);
    assert_float_equal(l->intensity, 10.0f * sqrtf(2.0f), 1e-4);
}

static void test_hue_saturation(void **state)
{
    float rgb[3], h, sat, v;
    interaction_hsv_to_rgb(0.0f, 1.0f, 1.0f, rgb);
    assert_float_equal(rgb[0], 1, 1e-6); assert_float_equal(rgb[1], 0, 1e-6); assert_float_equal(rgb[2], 0, 1e-6);
    interaction_hsv_to_rgb(1.0f / 3, 1.0f, 1.0f, rgb);
    assert_float_equal(rgb[0], 0, 1e-6); assert_float_equal(rgb[1], 1, 1e-6);
    interaction_hsv_to_rgb(0.5f, 0.5f, 0.8f, rgb);     /* pastel cyan */
    assert_float_equal(rgb[0], 0.4f, 1e-6); assert_float_equal(rgb[1], 0.8f, 1e-6); assert_float_equal(rgb[2], 0.8f, 1e-6);
    interaction_rgb_to_hsv(rgb, &h, &sat, &v);
    assert_float_equal(h, 0.5f, 1e-6); assert_float_equal(sat, 0.5f, 1e-6); assert_float_equal(v, 0.8f, 1e-6);
    const float purple[3] = {0.6f, 0.2f, 0.9f};
    interaction_rgb_to_hsv(purple, &h, &sat, &v);
    interaction_hsv_to_rgb(h, sat, v, rgb);
    for (int i = 0; i < 3; i++)
        assert_float_equal(rgb[i], purple[i], 1e-6);

    interaction ia;
    interaction_init(&ia, &(interaction_desc){.first_layout = INTERACTION_LIGHTING});
    frame_params p;
    test_frame_init(&p);                                   /* red light: h 0, s 1 */
    input_state s = state_at((float[]){0.2f, 1.1f, -0.5f}, 0.0f);
    interaction_update(&ia, &s, 0.0, &p);
    /* inside the dead zone nothing moves */
    s.axes[INPUT_AXIS_X] = 0.1f;
    s.axes[INPUT_AXIS_Y] = -0.12f;
    assert_int_equal(interaction_update(&ia, &s, 1.0, &p), 0);
    /* full Y for 1 s: hue + 0.25 turns (red -> chartreuse) */
    s.axes[INPUT_AXIS_X] = 0.0f;
    s.axes[INPUT_AXIS_Y] = 1.0f;
    assert_int_equal(interaction_update(&ia, &s, 1.0, &p), INTERACTION_CHANGED_LIGHT);
    assert_float_equal(p.lights[0].color[0], 0.5f, 1e-5);
    assert_float_equal(p.lights[0].color[1], 1.0f, 1e-5);
    assert_float_equal(p.lights[0].color[2], 0.0f, 1e-5);
    /* full -X for 1 s: saturation 1 -> 0.5 */
    s.axes[INPUT_AXIS_Y] = 0.0f;
    s.axes[INPUT_AXIS_X] = -1.0f;
    interaction_update(&ia, &s, 1.0, &p);
    interaction_rgb_to_hsv(p.lights[0].color, &h, &sat, &v);
    assert_float_equal(h, 0.25f, 1e-5);
    assert_float_equal(sat, 0.5f, 1e-5);
    assert_float_equal(v, 1.0f, 1e-6);
    /* saturation clamps at 0, hue wraps */
    interaction_update(&ia, &s, 10.0, &p);
    assert_float_equal(p.lights[0].color[0], 1.0f, 1e-6);
    assert_float_equal(p.lights[0].color[2], 1.0f, 1e-6);
    s.axes[INPUT_AXIS_X] = 1.0f;
    s.axes[INPUT_AXIS_Y] = -1.0f;
    interaction_update(&ia, &s, 3.0, &p);              /* hue 0.25 - 0.75 = -0.5 -> 0.5 */
    interaction_rgb_to_hsv(p.lights[0].color, &h, &sat, &v);
    assert_float_equal(h, 0.5f, 1e-5);
    assert_float_equal(sat, 1.0f, 1e-6);
}

static void test_settings(void **state)
{
    interaction ia;
    interaction_init(&ia, &(interaction_desc){.first_layout = INTERACTION_SETTINGS,
                                              .steps_max = 10});
    frame_params p;
    test_frame_init(&p);
    input_state s = state_at((float[]){0.2f, 1.1f, -0.5f}, 0.0f);
    interaction_update(&ia, &s, 0.0, &p);
    assert_int_equal(press(&ia, &s, &p, INPUT_BUTTON_M), INTERACTION_CHANGED_STEPS);
    assert_int_equal(p.lpv_steps, 9);
    press(&ia, &s, &p, INPUT_BUTTON_M);
    assert_int_equal(press(&ia, &s, &p, INPUT_BUTTON_M), 0); /* clamped at 10 */
    assert_int_equal(p.lpv_steps, 10);
    press(&ia, &s, &p, INPUT_BUTTON_L);
    assert_int_equal(p.lpv_steps, 9);
    /* lambda presets 0, 0.5, 0.8, 0.9, then back to 0 */
    const float expect[] = {0.8f, 0.9f, 0.0f, 0.5f};
    for (int i = 0; i < 4; i++) {
        assert_int_equal(press(&ia, &s, &p, INPUT_BUTTON_AUX), INTERACTION_CHANGED_LAMBDA);
        assert_float_equal(p.lambda_incr, expect[i], 0);
    }
    /* C switches the GI method round-robin in registry order (ILPV, none, vpl, ...), back to
     * ILPV after the last */
    assert_int_equal(p.gi, gi_method_find("ilpv"));
    assert_int_equal(press(&ia, &s, &p, INPUT_BUTTON_C), INTERACTION_CHANGED_GI);
    assert_int_equal(p.gi, gi_method_find("none"));
    press(&ia, &s, &p, INPUT_BUTTON_C);
    assert_int_equal(p.gi, gi_method_find("vpl"));
    for (int m = 3; m <= gi_method_count(); m++) {
        press(&ia, &s, &p, INPUT_BUTTON_C);
        assert_int_equal(p.gi, m % gi_method_count());
    }
    assert_int_equal(p.gi, gi_method_find("ilpv"));
    /* axes: X absorption, Y scattering, clamped to [0, 1] */
    s.axes[INPUT_AXIS_X] = 1.0f;
    s.axes[INPUT_AXIS_Y] = -1.0f;
    uint32_t c = interaction_update(&ia, &s, 0.4, &p);
    assert_int_equal(c, INTERACTION_CHANGED_ABSORPTION | INTERACTION_CHANGED_SCATTERING);
    assert_float_equal(p.absorption, 0.2f, 1e-6);
    assert_float_equal(p.scattering, 0.1f, 1e-6);
    interaction_update(&ia, &s, 10.0, &p);
    assert_float_equal(p.absorption, 1.0f, 0);
    assert_float_equal(p.scattering, 0.0f, 0);
    /* at the limits, holding the axis changes nothing further */
    assert_int_equal(interaction_update(&ia, &s, 1.0, &p), 0);
}

static void test_round_robin_and_change_only(void **state)
{
    interaction ia;
    interaction_init(&ia, &(interaction_desc){0});
    frame_params p;
    test_frame_init(&p);
    p.hud_layout = -1;
    input_state s = state_at((float[]){0.2f, 1.1f, -0.5f}, 0.0f);
    uint32_t c = interaction_update(&ia, &s, 0.0, &p);
    assert_int_equal(c, INTERACTION_CHANGED_HEAD | INTERACTION_CHANGED_WAND | INTERACTION_CHANGED_LAYOUT);
    assert_int_equal(p.hud_layout, INTERACTION_NAVIGATION);
    assert_float_equal(p.head[13], 1.7f, 0);
    /* the same input again: nothing to send */
    assert_int_equal(interaction_update(&ia, &s, 0.016, &p), 0);
    /* only the moved pose is reported */
    s.wand.position[0] = 0.25f;
    assert_int_equal(interaction_update(&ia, &s, 0.016, &p), INTERACTION_CHANGED_WAND);
    const int order[] = {INTERACTION_LIGHTING, INTERACTION_SETTINGS, INTERACTION_NAVIGATION,
                         INTERACTION_LIGHTING};
    for (int i = 0; i < 4; i++) {
        assert_int_equal(press(&ia, &s, &p, INPUT_BUTTON_R), INTERACTION_CHANGED_LAYOUT);
        assert_int_equal(p.hud_layout, order[i]);
        assert_int_equal(ia.layout, order[i]);
    }
    /* buttons of one layout do nothing in another: M in lighting is not "reset" */
    float nav[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 3, 0, 0, 1};
    memcpy(p.navigation, nav, sizeof nav);
    assert_int_equal(press(&ia, &s, &p, INPUT_BUTTON_M), INTERACTION_CHANGED_LIGHT);
    assert_float_equal(p.navigation[12], 3.0f, 0);
    /* holding C with no time passing moves nothing in navigation */
    press(&ia, &s, &p, INPUT_BUTTON_R);
    press(&ia, &s, &p, INPUT_BUTTON_R);
    s.buttons = 1u << INPUT_BUTTON_C;
    assert_int_equal(interaction_update(&ia, &s, 0.0, &p), 0);
    /* a missing light is created when the lighting layout needs one */
    p.light_count = 0;
    press(&ia, &s, &p, INPUT_BUTTON_R);
    assert_int_equal(p.light_count, 1);
    assert_true(p.lights[0].enabled);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_speed_law),
        cmocka_unit_test(test_fly_along_wand),
        cmocka_unit_test(test_turn_by_dragging),
        cmocka_unit_test(test_flashlight_pose),
        cmocka_unit_test(test_hue_saturation),
        cmocka_unit_test(test_settings),
        cmocka_unit_test(test_round_robin_and_change_only),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
