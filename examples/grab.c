/* grab: pick up the default room's boxes with the wand and put them somewhere else.
 *
 * The application takes the wand's C button (desc.buttons: the master's interaction
 * layouts no longer fly with it). Pressing C picks the object whose box the wand's ray
 * meets first (cavelight_object_bounds() through its model); while C is held the object
 * follows the wand as if fixed to it; releasing puts it down where it is. Shared state:
 * "held" (the object's name, "" when none) and the ray ("ray_from", "ray_to"), which
 * every node draws as a line, red while it holds something: lit and hidden behind the
 * scene like any surface. Run: cavelight-master --config CFG --spawn-local --input
 * configs/input/desk.json --app build/examples/grab.so (docs/app.md). */
#include <cavelight/app.h>
#include <math.h>
#include <string.h>

enum { REACH_M = 4 };

static cavelight_key held_key, from_key, to_key;
static int held = -1;
static float wand_at_grab[16], offset_at_grab[16];

static void init(cavelight_app *app)
{
    held_key = cavelight_key_string(app, "held", 47);
    from_key = cavelight_key_vector(app, "ray_from", 3, NULL);
    to_key = cavelight_key_vector(app, "ray_to", 3, NULL);
}

/* Where the ray o + t d (world) enters object k's box, or -1: the ray taken into the
 * object's own space (its model's inverse), then the slab test. */
static float hit(cavelight_app *app, int k, const float o[3], const float d[3])
{
    float lo[3], hi[3], model[16], inv[16], p[3], q[3], tip[3] = {o[0] + d[0], o[1] + d[1], o[2] + d[2]};
    if (cavelight_object_visible(app, k) != 1 || cavelight_object_bounds(app, k, lo, hi) != 0 ||
        cavelight_object_model(app, k, model) != 0 || cavelight_mat4_inverse(model, inv) != 0)
        return -1;
    cavelight_mat4_point(inv, o, p);
    cavelight_mat4_point(inv, tip, q);
    float near = 0, far = INFINITY;
    for (int a = 0; a < 3; a++) {
        float dir = q[a] - p[a], t0 = (lo[a] - p[a]) / dir, t1 = (hi[a] - p[a]) / dir;
        if (dir == 0 && (p[a] < lo[a] || p[a] > hi[a]))
            return -1;
        if (dir != 0) {
            near = fmaxf(near, fminf(t0, t1));
            far = fminf(far, fmaxf(t0, t1));
        }
    }
    return near <= far ? near : -1;
}

static void update(cavelight_app *app, const cavelight_input *in)
{
    float wand[16];
    cavelight_mat4_mul(in->navigation, in->wand, wand);
    const float o[3] = {wand[12], wand[13], wand[14]}, d[3] = {-wand[8], -wand[9], -wand[10]};
    float reach = REACH_M;
    int pick = -1;
    for (int k = 0; k < cavelight_object_count(app); k++) {
        float t = hit(app, k, o, d);
        if (t >= 0 && t < reach) {
            reach = t;
            pick = k;
        }
    }
    int c = 1u << CAVELIGHT_BUTTON_C;
    if ((in->pressed & c) && pick >= 0 && in->wand_valid) {
        held = pick;
        memcpy(wand_at_grab, wand, sizeof wand);
        cavelight_object_offset(app, held, offset_at_grab);
    }
    if (!(in->buttons & c))
        held = -1;
    if (held >= 0) { /* offset = W_now W_grab^-1 offset_grab: fixed to the wand */
        float inv[16], m[16];
        cavelight_mat4_inverse(wand_at_grab, inv);
        cavelight_mat4_mul(wand, inv, m);
        cavelight_mat4_mul(m, offset_at_grab, m);
        cavelight_object_set_offset(app, held, m);
    }
    const float to[3] = {o[0] + reach * d[0], o[1] + reach * d[1], o[2] + reach * d[2]};
    cavelight_set_string(app, held_key, held >= 0 ? cavelight_object_name(app, held) : "");
    cavelight_set_vector(app, from_key, 3, o);
    cavelight_set_vector(app, to_key, 3, to);
}

static void draw(cavelight_app *app, const cavelight_draw *dr)
{
    cavelight_vertex ray[2] = {0};
    cavelight_get_vector(app, from_key, 3, ray[0].position);
    cavelight_get_vector(app, to_key, 3, ray[1].position);
    int holding = cavelight_get_string(app, held_key)[0] != '\0';
    for (int v = 0; v < 2; v++) {
        ray[v].color[0] = 1.0f;
        ray[v].color[1] = ray[v].color[2] = holding ? 0.1f : 1.0f;
    }
    cavelight_draw_lines(app, dr, ray, 2);
}

cavelight_app_desc cavelight_app_main(void)
{
    return (cavelight_app_desc){.name = "grab", .buttons = 1u << CAVELIGHT_BUTTON_C, .init = init,
                                .update = update, .draw = draw};
}
