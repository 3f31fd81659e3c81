/* HUD description: indicator colours per active layout, the cone in the spot's colour
 * and pose, bar values and the lambda highlight. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <string.h>

#include "frame/hud.h"

static void params(frame_params *p)
{
    memset(p, 0, sizeof *p);
    for (int i = 0; i < 16; i += 5)
        p->head[i] = p->wand[i] = p->navigation[i] = 1.0f;
    p->light_count = 1;
    p->lights[0] = (frame_light){.enabled = 1, .position = {1, 2, 3}, .direction = {0, -1, 0},
                                 .color = {0.4f, 0.2f, 0.1f}, .intensity = 10,
                                 .outer_angle = 0.6f, .inner_angle = 0.5f};
    p->lpv_steps = 8;
    p->absorption = 0.25f;
    p->scattering = 1.5f;
    p->lambda_incr = 0.0f;
}

static void test_indicators(void **state)
{
    frame_params p;
    params(&p);
    hud h;
    for (int layout = 0; layout < 3; layout++) {
        p.hud_layout = layout;
        hud_describe(&p, 32, &h);
        assert_true(h.visible);
        for (int i = 0; i < HUD_INDICATOR_COUNT; i++) {
            assert_int_equal(h.indicators[i].active, i == layout);
            if (i != HUD_SHAPE_CONE)
                assert_float_equal(h.indicators[i].color[1], i == layout ? HUD_WHITE : HUD_GREY, 0);
        }
        /* the cone keeps the spot's colour (brightest component at 1) in every layout */
        assert_float_equal(h.indicators[HUD_SHAPE_CONE].color[0], 1.0f, 1e-6);
        assert_float_equal(h.indicators[HUD_SHAPE_CONE].color[1], 0.5f, 1e-6);
        assert_float_equal(h.indicators[HUD_SHAPE_CONE].color[2], 0.25f, 1e-6);
    }
    assert_true(h.has_light);
    assert_float_equal(h.light_position[2], 3.0f, 0);
    assert_float_equal(h.light_angle, 0.6f, 0);
    p.hud_layout = -1;
    hud_describe(&p, 32, &h);
    assert_false(h.visible);
    p.lights[0].enabled = 0;
    hud_describe(&p, 32, &h);
    assert_false(h.has_light);
}

static void test_bars_and_anchor(void **state)
{
    frame_params p;
    params(&p);
    p.hud_layout = 2;
    p.navigation[12] = 5.0f;     /* CAVE moved 5 m along world X */
    p.wand[13] = 1.2f;           /* wand 1.2 m up in the CAVE */
    hud h;
    hud_describe(&p, 16, &h);
    assert_int_equal(h.bars[0].letter, 'A');
    assert_float_equal(h.bars[0].value, 0.25f, 0);
    assert_float_equal(h.bars[1].value, 1.0f, 0);       /* clamped */
    assert_float_equal(h.bars[2].value, 0.0f, 0);
    assert_float_equal(h.bars[2].color[0], HUD_GREY, 0); /* not incremental */
    assert_float_equal(h.bars[3].value, 0.5f, 0);       /* 8 steps / 16 cells */
    p.lambda_incr = 0.8f;
    hud_describe(&p, 32, &h);
    assert_float_equal(h.bars[2].value, 0.8f, 1e-6);
    assert_float_equal(h.bars[2].color[0], HUD_WHITE, 0);
    assert_float_equal(h.bars[3].value, 0.25f, 0);       /* 8 steps / 32 cells */
    assert_float_equal(h.wand_world[12], 5.0f, 0);
    assert_float_equal(h.wand_world[13], 1.2f, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_indicators),
        cmocka_unit_test(test_bars_and_anchor),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
