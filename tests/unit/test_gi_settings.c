/* gi_settings: the registry's options as every program sees them: names unique and
 * matching their store keys, each method's rows inside its struct, the one parser with its
 * reasons, the clamp a node applies, what rebuilds a method, the config's "settings". */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "gi/gi_settings.h"
#include "gi/ilpv/ilpv_settings.h"
#include "gi/vpl/vpl_settings.h"

static void test_registry(void **state)
{
    assert_true(gi_method_count() >= 3);
    assert_int_equal(gi_method_find("ilpv"), 0); /* every frame's default */
    assert_string_equal(gi_method_names()[gi_method_find("vpl")], "vpl");
    assert_int_equal(gi_method_find("bogus"), -1);
    params_schema schema;
    gi_params_schema(&schema);
    for (int i = 0; i < gi_option_count(); i++) {
        const gi_option *o = gi_option_at(i);
        for (int j = 0; j < i; j++) /* one name, one option */
            assert_true(strcmp(o->row->name, gi_option_at(j)->row->name) != 0);
        int k = params_schema_find(&schema, o->row->name); /* and one store key */
        assert_true(k >= 0);
        assert_int_equal(schema.keys[k].type, o->row->kind == SETTING_FLOAT ? PARAMS_T_F32 : PARAMS_T_I32);
        if (o->method >= 0) { /* a method's row lies inside its struct */
            assert_true(o->slot >= 0 && o->slot < FRAME_GI_SETTINGS_MAX);
            assert_true(o->row->offset + 4 <= gi_method_at(o->method)->struct_size);
            assert_int_equal(o->row->offset % 4, 0);
        }
    }
}

static void test_set_and_read(void **state)
{
    frame_params p;
    frame_params_default(&p);
    vpl_settings v;
    vpl_settings_get(&p, &v); /* unset: the defaults */
    assert_int_equal(v.count, VPL_COUNT_DEFAULT);
    assert_int_equal(v.visibility, VPL_VISIBILITY_EXACT);
    assert_null(gi_set(&p, "vpl-visibility", "ism-splat"));
    assert_null(gi_set(&p, "vpl-count", "1024"));
    assert_null(gi_set(&p, "steps", "4")); /* a frame field */
    assert_null(gi_set(&p, "gi", "vpl"));
    assert_null(gi_set_number(&p, "lattice", 24));
    vpl_settings_get(&p, &v);
    assert_int_equal(v.count, 1024);
    assert_int_equal(v.visibility, VPL_VISIBILITY_ISM_SPLAT);
    assert_int_equal(p.lpv_steps, 4);
    assert_int_equal(p.gi, gi_method_find("vpl"));
    ilpv_settings l;
    ilpv_settings_get(&p, &l);
    assert_int_equal(l.lattice, 24);
    char text[32];
    assert_string_equal(gi_get_text(&p, "vpl-visibility", text, sizeof text), "ism-splat");
    assert_string_equal(gi_set(&p, "vpl-count", "5000"), "a whole number in 64..4096");
    assert_string_equal(gi_set(&p, "vpl-cuont", "64"), "not a setting (did you mean vpl-count?)");
    assert_string_equal(gi_set(&p, "exposure", "0"), "a number in [1e-06, 1e+06]");
    assert_int_equal(v.count, 1024); /* a refused value changes nothing */
}

static void test_sanitize_and_rebuild(void **state)
{
    frame_params a, b;
    frame_params_default(&a);
    assert_int_equal(gi_frame_sanitize(&a), 0);
    b = a;
    b.gi = 99;
    b.gi_settings[gi_option_find("vpl-count")->slot] = (frame_gi_setting){1, {.i = 1 << 20}};
    b.gi_settings[gi_option_find("ism-size")->slot] = (frame_gi_setting){1, {.i = 100}};
    assert_int_equal(gi_frame_sanitize(&b), 3);
    assert_int_equal(b.gi, 0);
    assert_int_equal(gi_option_get(gi_option_find("vpl-count"), &b).i, VPL_COUNT_MAX);
    assert_int_equal(gi_option_get(gi_option_find("ism-size"), &b).i, 64);
    /* The lattice rebuilds ILPV, the count does not rebuild vpl, the visibility does. */
    int ilpv = gi_method_find("ilpv"), vpl = gi_method_find("vpl");
    b = a;
    gi_set(&b, "lattice", "20");
    assert_true(gi_rebuild_needed(ilpv, &a, &b));
    assert_false(gi_rebuild_needed(vpl, &a, &b));
    b = a;
    gi_set(&b, "vpl-count", "64");
    assert_false(gi_rebuild_needed(vpl, &a, &b));
    gi_set(&b, "vpl-visibility", "ism");
    assert_true(gi_rebuild_needed(vpl, &a, &b));
    /* An unset slot and a set one at the default are the same setting. */
    b = a;
    gi_set(&b, "lattice", "32");
    assert_false(gi_rebuild_needed(ilpv, &a, &b));
}

static void test_config_settings(void **state)
{
    cluster_config cfg = {.path = "c.json", .setting_count = 2,
                          .settings = {{"gi", "vpl"}, {"vpl-interleave", "4"}}};
    frame_params p;
    frame_params_default(&p);
    char err[256];
    assert_int_equal(gi_set_config(&cfg, &p, err, sizeof err), 0);
    assert_int_equal(p.gi, gi_method_find("vpl"));
    assert_int_equal(gi_option_get(gi_option_find("vpl-interleave"), &p).i, 4);
    cfg.settings[1] = (cluster_setting){"vpl-interleave", "9"};
    assert_int_equal(gi_set_config(&cfg, &p, err, sizeof err), -1);
    assert_string_equal(err, "cluster config c.json: settings.vpl-interleave: 9: a whole number in 0..8");
    /* Two settings that exclude each other: one line. */
    cfg.settings[1] = (cluster_setting){"lattice", "16"};
    cfg.settings[2] = (cluster_setting){"lattice-cells", "4096"};
    cfg.setting_count = 3;
    frame_params_default(&p);
    assert_int_equal(gi_set_config(&cfg, &p, err, sizeof err), -1);
    assert_non_null(strstr(err, "give --lattice"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_registry),
        cmocka_unit_test(test_set_and_read),
        cmocka_unit_test(test_sanitize_and_rebuild),
        cmocka_unit_test(test_config_settings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
