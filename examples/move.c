/* move: the smallest application. The default room's tall box circles on the floor, one
 * turn every 8 s of the session's clock: offset = translation(0.5 cos a - 0.5, 0,
 * 0.5 sin a), a = 2 pi t / 8. Every node draws it there, its shadow and indirect light
 * follow. Run: cavelight-master --config CFG --spawn-local --app build/examples/move.so */
#include <cavelight/app.h>
#include <math.h>

static int box;

static void init(cavelight_app *app)
{
    box = cavelight_object_find(app, "tall_box");
}

static void update(cavelight_app *app, const cavelight_input *in)
{
    double a = 2.0 * 3.14159265358979 * in->time / 8.0;
    float m[16];
    cavelight_mat4_translation(m, (float)(0.5 * cos(a) - 0.5), 0.0f, (float)(0.5 * sin(a)));
    cavelight_object_set_offset(app, box, m);
}

cavelight_app_desc cavelight_app_main(void)
{
    return (cavelight_app_desc){.name = "move", .init = init, .update = update};
}
