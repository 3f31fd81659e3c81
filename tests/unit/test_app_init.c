/* An application's init does what docs/app.md says it is for (tests/apps/initquery.so on
 * the default room): an object's bounds are valid there (the tall box's height comes
 * back), and a call init may not make (setting an offset) returns -1 to the application
 * without stopping the session. A refused key registration does stop it, and the line
 * names that registration, not the refused call after it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "app/app_host.h"
#include "scene/scene_load.h"

#define INITQUERY CAVELIGHT_BINARY_DIR "/tests/apps/initquery.so"

static double initial(const params_schema *schema, const char *name)
{
    static params_store store;
    params_init(&store, schema);
    int key = params_schema_find(schema, name);
    assert_true(key >= 0);
    double v = 0;
    assert_int_equal(params_get(&store, key, &v, sizeof v), 0);
    return v;
}

static void test_objects_in_init(void **state)
{
    (void)state;
    scene sc;
    char err[512];
    assert_int_equal(scene_load("default", &sc, err, sizeof err), 0);
    app_host_desc ad = {.path = INITQUERY, .role = CAVELIGHT_ROLE_MASTER, .process = "master",
                        .scene = &sc, .quiet = 1};
    app_host *h = app_host_load(&ad, err, sizeof err);
    assert_non_null(h);
    if (app_host_init(h, err, sizeof err) != 0)
        fail_msg("init refused: %s", err);
    static params_schema schema;
    params_schema_init(&schema);
    assert_int_equal(app_host_add_keys(h, &schema, err, sizeof err), 0);
    int box = scene_object_find(&sc, "tall_box");
    assert_true(box >= 0);
    double height = initial(&schema, "app.bounds");
    printf("tall_box height from init: %.3f m\n", height);
    assert_true(height > 0.1 && height < 3.0);
    assert_true(initial(&schema, "app.set_refused") == 1.0);
    app_host_destroy(h);
    scene_free(&sc);
}

static void test_key_refusal_named(void **state)
{
    (void)state;
    scene sc;
    char err[512];
    assert_int_equal(scene_load("default", &sc, err, sizeof err), 0);
    setenv("CAVELIGHT_TEST_BAD_KEY", "1", 1);
    app_host_desc ad = {.path = INITQUERY, .role = CAVELIGHT_ROLE_MASTER, .process = "master",
                        .scene = &sc, .quiet = 1};
    app_host *h = app_host_load(&ad, err, sizeof err);
    assert_non_null(h);
    assert_int_equal(app_host_init(h, err, sizeof err), -1);
    unsetenv("CAVELIGHT_TEST_BAD_KEY");
    printf("%s\n", err);
    assert_non_null(strstr(err, "init registered a key that was refused (cavelight_key_"));
    assert_null(strstr(err, "visible"));
    app_host_destroy(h);
    scene_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_objects_in_init),
        cmocka_unit_test(test_key_refusal_named),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
