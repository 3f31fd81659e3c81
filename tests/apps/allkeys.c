/* allkeys: a test application with a key of every type, each changed every frame from the
 * input's frame number and time, so that a late joiner's snapshot, a replay and the wire
 * have something of each to carry. On the master, frame 1 also tries what an application
 * may get wrong; the refusals' return values go into the key "refusals" (a blob of one
 * int per try, 0 where the call was refused as it must be). */
#include <cavelight/app.h>
#include <stdio.h>
#include <string.h>

enum { TRIES = 9 };

static cavelight_key number, vec2, vec3, vec4, matrix, text, blob, refusals, late;

static void init(cavelight_app *app)
{
    const float v[4] = {1, 2, 3, 4};
    number = cavelight_key_number(app, "number", 1.5);
    vec2 = cavelight_key_vector(app, "vec2", 2, v);
    vec3 = cavelight_key_vector(app, "vec3", 3, v);
    vec4 = cavelight_key_vector(app, "vec4", 4, NULL);
    matrix = cavelight_key_matrix(app, "matrix", NULL);
    text = cavelight_key_string(app, "text", 32);
    blob = cavelight_key_blob(app, "blob", 64);
    refusals = cavelight_key_blob(app, "refusals", TRIES * sizeof(int));
}

/* Each call that must be refused: 1 when it was. */
static void misbehave(cavelight_app *app)
{
    int r[TRIES];
    float nan = 0.0f / 0.0f, m[16] = {0};
    char long_text[40];
    memset(long_text, 'x', sizeof long_text - 1);
    long_text[sizeof long_text - 1] = 0;
    r[0] = cavelight_set_number(app, text, 1.0) == -1;          /* a string is not a number */
    r[1] = cavelight_set_vector(app, vec3, 2, m) == -1;          /* 2 floats for a vec3 */
    r[2] = cavelight_set_string(app, text, long_text) == -1;     /* 39 bytes, capacity 32 */
    r[3] = cavelight_set_string(app, text, "\xff\xfe") == -1;    /* not UTF-8 */
    r[4] = cavelight_set_number(app, number, nan) == -1;         /* not finite */
    r[5] = cavelight_set_number(app, 999, 1.0) == -1;            /* no such key */
    r[6] = (late = cavelight_key_number(app, "late", 0)) == -1;  /* registered outside init */
    r[7] = cavelight_object_set_offset(app, 999, m) == -1;       /* no such object */
    r[8] = cavelight_set_blob(app, blob, long_text, 65) == -1;   /* 65 bytes, capacity 64 */
    cavelight_set_blob(app, refusals, r, sizeof r);
}

static void update(cavelight_app *app, const cavelight_input *in)
{
    float f = (float)in->frame, v[4] = {f, f + 1, f + 2, f + 3}, m[16];
    cavelight_mat4_translation(m, f, 2 * f, 3 * f);
    cavelight_set_number(app, number, in->time);
    cavelight_set_vector(app, vec2, 2, v);
    cavelight_set_vector(app, vec3, 3, v);
    cavelight_set_vector(app, vec4, 4, v);
    cavelight_set_matrix(app, matrix, m);
    char s[32];
    snprintf(s, sizeof s, "frame %llu \xc3\xa4", (unsigned long long)in->frame); /* "ä": UTF-8 */
    cavelight_set_string(app, text, s);
    unsigned char b[64];
    for (int i = 0; i < 64; i++)
        b[i] = (unsigned char)(in->frame * 7 + (uint64_t)i);
    cavelight_set_blob(app, blob, b, 1 + in->frame % 64);
    if (in->frame == 1)
        misbehave(app);
}

/* A node may read but never set: the set is refused, the value stays the master's. */
static void frame(cavelight_app *app)
{
    cavelight_set_number(app, number, -1.0);
}

cavelight_app_desc cavelight_app_main(void)
{
    return (cavelight_app_desc){.name = "allkeys", .init = init, .update = update, .frame = frame};
}
