/* initquery: a test application whose init asks what docs/app.md says init is for (find an
 * object, read its bounds) and makes one call init may not (an object's offset is set in
 * update only). The key "bounds" starts at the default room's tall_box's height (its
 * bounds' hi[1] - lo[1], -1 when a call failed); "set_refused" at 1 when the set was
 * refused. With CAVELIGHT_TEST_BAD_KEY set, init also registers a key with an empty name
 * (refused), then makes another refused call: the session must stop naming the key. */
#include <cavelight/app.h>
#include <stdlib.h>

static void init(cavelight_app *app)
{
    int box = cavelight_object_find(app, "tall_box");
    float lo[3], hi[3], m[16];
    double height = box >= 0 && cavelight_object_bounds(app, box, lo, hi) == 0 ? hi[1] - lo[1] : -1.0;
    cavelight_mat4_translation(m, 0, 1, 0);
    int set_refused = cavelight_object_set_offset(app, box, m) == -1;
    if (getenv("CAVELIGHT_TEST_BAD_KEY")) {
        cavelight_key_number(app, "", 0);
        cavelight_object_set_visible(app, box, 0);
    }
    cavelight_key_number(app, "bounds", height);
    cavelight_key_number(app, "set_refused", set_refused);
}

cavelight_app_desc cavelight_app_main(void)
{
    return (cavelight_app_desc){.name = "initquery", .init = init};
}
