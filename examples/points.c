/* points: an application that draws its own data set, a spiral of 2000 points and the
 * edges of the box around it, lit by the room's lamp and indirect light like its walls and
 * hidden behind the room's boxes where they stand in front. The master turns it (the key
 * "angle", 0.25 turns a second of the session's clock); every node draws the points
 * where the angle says, so all walls show the same spiral. Run: cavelight-master
 * --config CFG --spawn-local --app build/examples/points.so */
#include <cavelight/app.h>
#include <math.h>

enum { POINTS = 2000 };
static const float CENTRE[3] = {-0.9f, 1.2f, -0.9f}, RADIUS = 0.45f, HEIGHT = 1.6f;

static cavelight_key angle;
static cavelight_vertex spiral[POINTS], edges[24];

static void init(cavelight_app *app)
{
    angle = cavelight_key_number(app, "angle", 0.0);
}

static void update(cavelight_app *app, const cavelight_input *in)
{
    cavelight_set_number(app, angle, 2.0 * 3.14159265358979 * 0.25 * in->time);
}

/* The frame's spiral and its box, turned by the frame's angle. */
static void frame(cavelight_app *app)
{
    double a = cavelight_get_number(app, angle);
    for (int i = 0; i < POINTS; i++) {
        double u = (double)i / POINTS, t = a + 12.0 * 3.14159265358979 * u;
        cavelight_vertex *v = &spiral[i];
        v->position[0] = CENTRE[0] + (float)(RADIUS * cos(t));
        v->position[1] = CENTRE[1] + (float)(HEIGHT * (u - 0.5));
        v->position[2] = CENTRE[2] + (float)(RADIUS * sin(t));
        v->color[0] = (float)u;          /* normal zero: the points face the eye */
        v->color[1] = 0.3f;
        v->color[2] = (float)(1.0 - u);
    }
    for (int e = 0; e < 12; e++) { /* the box's 12 edges: corners differing in one axis */
        int axis = e / 4, other = e % 4;
        for (int end = 0; end < 2; end++) {
            cavelight_vertex *v = &edges[2 * e + end];
            for (int k = 0; k < 3; k++) {
                int bit = k == axis ? end : (k == (axis + 1) % 3 ? other & 1 : other >> 1);
                float half = k == 1 ? HEIGHT / 2 : RADIUS;
                v->position[k] = CENTRE[k] + (bit ? half : -half);
                v->color[k] = 0.9f;
            }
        }
    }
}

static void draw(cavelight_app *app, const cavelight_draw *d)
{
    cavelight_draw_points(app, d, spiral, POINTS, 3.0f);
    cavelight_draw_lines(app, d, edges, 24);
}

cavelight_app_desc cavelight_app_main(void)
{
    return (cavelight_app_desc){.name = "points", .init = init, .update = update, .frame = frame, .draw = draw};
}
