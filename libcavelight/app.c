/* libcavelight: the functions of cavelight/app.h an application calls. Each checks its
 * arguments and forwards to the process that loaded the application (app_abi.h); the
 * matrix helpers are here whole. */
#include "app/app_abi.h"
#include "base/mat4.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Which ABI this library speaks: the host compares it with its own before init. */
int cavelight_library_abi(void) { return CAVELIGHT_APP_ABI; }

static int usable(const cavelight_app *app) { return app && app->abi == CAVELIGHT_APP_ABI && app->ops; }

static int refuse(const cavelight_app *app, const char *what)
{
    if (usable(app))
        app->ops->refuse(app->host, what);
    else
        fprintf(stderr, "cavelight app: %s: not a handle a cavelight process passed\n", what);
    return -1;
}

cavelight_role cavelight_app_role(const cavelight_app *app) { return usable(app) ? app->role : 0; }
void *cavelight_app_user(const cavelight_app *app) { return usable(app) ? app->desc.user : NULL; }
const char *cavelight_app_process(const cavelight_app *app) { return usable(app) ? app->process : ""; }

const char *cavelight_last_error(const cavelight_app *app)
{
    return usable(app) ? app->ops->last_error(app->host) : "not a cavelight handle";
}

/* ---- keys ------------------------------------------------------------------------- */

static cavelight_key add(cavelight_app *app, const char *name, app_key_kind kind, int n, size_t capacity,
                         const void *initial)
{
    if (!usable(app) || !name)
        return refuse(app, "cavelight_key_*(): no name");
    return app->ops->key_add(app->host, name, kind, n, capacity, initial);
}

cavelight_key cavelight_key_number(cavelight_app *app, const char *name, double initial)
{
    return add(app, name, APP_KEY_NUMBER, 1, 0, &initial);
}

cavelight_key cavelight_key_vector(cavelight_app *app, const char *name, int n, const float *initial)
{
    if (n < 2 || n > 4)
        return refuse(app, "cavelight_key_vector(): a vector has 2 to 4 floats");
    return add(app, name, APP_KEY_VECTOR, n, 0, initial);
}

cavelight_key cavelight_key_matrix(cavelight_app *app, const char *name, const float *initial)
{
    float id[16];
    cavelight_mat4_identity(id);
    return add(app, name, APP_KEY_MATRIX, 16, 0, initial ? initial : id);
}

cavelight_key cavelight_key_string(cavelight_app *app, const char *name, size_t capacity)
{
    return add(app, name, APP_KEY_STRING, 0, capacity, NULL);
}

cavelight_key cavelight_key_blob(cavelight_app *app, const char *name, size_t capacity)
{
    return add(app, name, APP_KEY_BLOB, 0, capacity, NULL);
}

cavelight_key cavelight_key_find(const cavelight_app *app, const char *name)
{
    return usable(app) && name ? app->ops->key_find(app->host, name) : -1;
}

static int set(cavelight_app *app, cavelight_key key, app_key_kind kind, int n, const void *data, size_t len)
{
    if (!usable(app))
        return refuse(app, "cavelight_set_*()");
    if (!data)
        return refuse(app, "cavelight_set_*(): no value");
    return app->ops->key_set(app->host, key, kind, n, data, len);
}

int cavelight_set_number(cavelight_app *app, cavelight_key key, double v)
{
    return set(app, key, APP_KEY_NUMBER, 1, &v, sizeof v);
}

int cavelight_set_vector(cavelight_app *app, cavelight_key key, int n, const float *v)
{
    return set(app, key, APP_KEY_VECTOR, n, v, (size_t)(n > 0 ? n : 0) * sizeof(float));
}

int cavelight_set_matrix(cavelight_app *app, cavelight_key key, const float *m)
{
    return set(app, key, APP_KEY_MATRIX, 16, m, 16 * sizeof(float));
}

int cavelight_set_string(cavelight_app *app, cavelight_key key, const char *s)
{
    return set(app, key, APP_KEY_STRING, 0, s, s ? strlen(s) : 0);
}

int cavelight_set_blob(cavelight_app *app, cavelight_key key, const void *data, size_t len)
{
    static const char empty = 0;
    return set(app, key, APP_KEY_BLOB, 0, len == 0 && !data ? &empty : data, len);
}

static const void *get(cavelight_app *app, cavelight_key key, app_key_kind kind, int n, size_t *len)
{
    size_t ignored;
    return usable(app) ? app->ops->key_get(app->host, key, kind, n, len ? len : &ignored) : NULL;
}

double cavelight_get_number(cavelight_app *app, cavelight_key key)
{
    const double *v = get(app, key, APP_KEY_NUMBER, 1, NULL);
    return v ? *v : 0.0;
}

int cavelight_get_vector(cavelight_app *app, cavelight_key key, int n, float *out)
{
    const float *v = out ? get(app, key, APP_KEY_VECTOR, n, NULL) : NULL;
    if (!v)
        return -1;
    memcpy(out, v, (size_t)n * sizeof(float));
    return 0;
}

int cavelight_get_matrix(cavelight_app *app, cavelight_key key, float *out)
{
    const float *v = out ? get(app, key, APP_KEY_MATRIX, 16, NULL) : NULL;
    if (!v)
        return -1;
    memcpy(out, v, 16 * sizeof(float));
    return 0;
}

const char *cavelight_get_string(cavelight_app *app, cavelight_key key)
{
    return get(app, key, APP_KEY_STRING, 0, NULL);
}

const void *cavelight_get_blob(cavelight_app *app, cavelight_key key, size_t *len)
{
    return get(app, key, APP_KEY_BLOB, 0, len);
}

/* ---- objects ---------------------------------------------------------------------- */

int cavelight_object_count(const cavelight_app *app)
{
    return usable(app) ? app->ops->object_count(app->host) : 0;
}

int cavelight_object_find(const cavelight_app *app, const char *name)
{
    return usable(app) && name ? app->ops->object_find(app->host, name) : -1;
}

const char *cavelight_object_name(const cavelight_app *app, int object)
{
    return usable(app) ? app->ops->object_name(app->host, object) : NULL;
}

int cavelight_object_set_offset(cavelight_app *app, int object, const float *m)
{
    if (!usable(app) || !m)
        return refuse(app, "cavelight_object_set_offset(): no matrix");
    return app->ops->object_set(app->host, object, m, -1);
}

int cavelight_object_set_visible(cavelight_app *app, int object, int visible)
{
    if (!usable(app))
        return refuse(app, "cavelight_object_set_visible()");
    return app->ops->object_set(app->host, object, NULL, visible != 0);
}

static int object_get(const cavelight_app *app, int object, app_object_part part, float *out)
{
    if (!usable(app) || !out)
        return -1;
    return app->ops->object_get(app->host, object, part, out);
}

int cavelight_object_offset(cavelight_app *app, int object, float *out)
{
    return object_get(app, object, APP_OBJECT_OFFSET, out);
}

int cavelight_object_model(cavelight_app *app, int object, float *out)
{
    return object_get(app, object, APP_OBJECT_MODEL, out);
}

int cavelight_object_visible(cavelight_app *app, int object)
{
    float v = 0;
    return object_get(app, object, APP_OBJECT_VISIBLE, &v) == 0 ? v != 0 : -1;
}

int cavelight_object_bounds(const cavelight_app *app, int object, float *lo, float *hi)
{
    float b[6];
    if (!lo || !hi || object_get(app, object, APP_OBJECT_BOUNDS, b) != 0)
        return -1;
    memcpy(lo, b, 3 * sizeof(float));
    memcpy(hi, b + 3, 3 * sizeof(float));
    return 0;
}

/* ---- drawing ---------------------------------------------------------------------- */

static int draw(cavelight_app *app, const cavelight_draw *d, int mode, const cavelight_vertex *v, int count,
                float size)
{
    if (!usable(app) || !d || (!v && count > 0) || count < 0)
        return refuse(app, "cavelight_draw_*(): no draw, or no vertices");
    return count ? app->ops->draw(app->host, d, mode, v, count, size) : 0;
}

int cavelight_draw_points(cavelight_app *app, const cavelight_draw *d, const cavelight_vertex *v, int count,
                          float size)
{
    return draw(app, d, 0, v, count, size);
}

int cavelight_draw_lines(cavelight_app *app, const cavelight_draw *d, const cavelight_vertex *v, int count)
{
    return draw(app, d, 1, v, count, 1.0f);
}

void *cavelight_gl_proc(cavelight_app *app, const char *name)
{
    return usable(app) && name ? app->ops->gl_proc(app->host, name) : NULL;
}

/* ---- matrices --------------------------------------------------------------------- */

void cavelight_mat4_identity(float *m)
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

void cavelight_mat4_translation(float *m, float x, float y, float z)
{
    cavelight_mat4_identity(m);
    m[12] = x;
    m[13] = y;
    m[14] = z;
}

void cavelight_mat4_rotation(float *m, float radians, float x, float y, float z)
{
    double len = sqrt((double)x * x + (double)y * y + (double)z * z);
    cavelight_mat4_identity(m);
    if (!(len > 0))
        return;
    double ax = x / len, ay = y / len, az = z / len, c = cos(radians), s = sin(radians), t = 1 - c;
    m[0] = (float)(t * ax * ax + c);      m[4] = (float)(t * ax * ay - s * az); m[8] = (float)(t * ax * az + s * ay);
    m[1] = (float)(t * ax * ay + s * az); m[5] = (float)(t * ay * ay + c);      m[9] = (float)(t * ay * az - s * ax);
    m[2] = (float)(t * ax * az - s * ay); m[6] = (float)(t * ay * az + s * ax); m[10] = (float)(t * az * az + c);
}

void cavelight_mat4_mul(const float *a, const float *b, float *out)
{
    mat4_mul(a, b, out);
}

int cavelight_mat4_inverse(const float *m, float *out)
{
    return mat4_affine_inverse(m, out);
}

void cavelight_mat4_point(const float *m, const float *p, float *out)
{
    mat4_transform_point(m, p, out);
}
