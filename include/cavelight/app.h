/* cavelight/app.h: a lab's own application inside cavelight's master and render nodes.
 *
 * An application is a shared object that defines cavelight_app_main(), which returns its
 * desc: callbacks, each optional (zero means none), in the style of sokol_app.h:
 *
 *   init      every process (the master and each render node), once, before the session:
 *             register the application's keys (cavelight_key_*()), find the scene's
 *             objects (cavelight_object_find()), make GL resources (nodes)
 *   update    the master, once per frame, with the frame's merged input (head, wand,
 *             buttons, axes, time): set keys and move objects. The only place that sets.
 *   frame     every render node, once per frame, when the frame's keys have arrived:
 *             read them (cavelight_get_*()); every node sees the same values
 *   draw      every render node, per screen and eye, into the G-buffer with the scene's
 *             depth bound and depth-tested: what it draws (cavelight_draw_points(),
 *             cavelight_draw_lines(), or its own GL through cavelight_gl_proc()) is lit
 *             like the scene (direct light, shadows, the GI method's indirect light),
 *             tone-mapped with it and hidden behind the scene's surfaces
 *   shutdown  every process, once, at the end
 *
 * Run it with `cavelight-master --app APP.so ...`: the master loads it, and passes it on to
 * the nodes it starts (`cavelight-node --app APP.so`). Every process must load the same
 * build: the master refuses a node whose application registered other keys.
 *
 * Keys are the application's shared state: numbers, vectors, matrices, strings and blobs
 * of a bounded size, registered in init with a name and an initial value. They live in
 * the master's parameter store beside the built-in keys (named "app.NAME"): versioned,
 * sent as deltas when they change, in the snapshot a late-joining node gets, and
 * reproduced by a replay of a recorded session. Every call that takes a key returns -1
 * (and says why in one line on stderr, cavelight_last_error() too) for a key of another
 * type, a value too large, a set outside update or on a node, a registration outside init.
 *
 * Objects are the scene's movable parts, by name: the glTF nodes whose subtree holds
 * triangles ("nodeN" when unnamed), the built-in room's "tall_box" and "low_box". An
 * object's offset is a transform of its triangles as loaded, applied after its parent's.
 *
 * Matrices are float[16], column-major (OpenGL's order). Positions are metres: the wand
 * and head in CAVE space, the scene and objects in world space (CAVE space through the
 * input's navigation matrix).
 *
 * Build: cc -shared -fPIC app.c $(pkg-config --cflags --libs cavelight) -o app.so
 * (docs/app.md: a tutorial from an empty file to a CAVE). */
#ifndef CAVELIGHT_APP_H
#define CAVELIGHT_APP_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CAVELIGHT_APP_VERSION 1

#if defined(__GNUC__)
#define CAVELIGHT_API __attribute__((visibility("default")))
#else
#define CAVELIGHT_API
#endif

typedef struct cavelight_app cavelight_app; /* this process's side of the application */

typedef enum cavelight_role {
    CAVELIGHT_ROLE_MASTER = 1,
    CAVELIGHT_ROLE_NODE = 2,
} cavelight_role;

/* Logical wand buttons (bits of cavelight_input.buttons and .pressed). */
enum {
    CAVELIGHT_BUTTON_L = 0,
    CAVELIGHT_BUTTON_M = 1,
    CAVELIGHT_BUTTON_R = 2,   /* the master's: next interaction layout */
    CAVELIGHT_BUTTON_C = 3,   /* trigger */
    CAVELIGHT_BUTTON_AUX = 4,
};

/* The frame's merged input, as the master's interaction layouts see it. */
typedef struct cavelight_input {
    uint64_t frame;           /* frames since the session started, from 0 */
    double time;              /* the session's clock, seconds (a replay: the recording's) */
    double dt;                /* seconds since the last frame */
    float head[16];           /* tracked head, CAVE space */
    float wand[16];           /* wand, CAVE space; it points along its -Z axis */
    int head_valid, wand_valid;
    uint32_t buttons;         /* bit b: button b held */
    uint32_t pressed;         /* bit b: button b went down since the last frame */
    float axes[4];            /* X, Y, Z, W in [-1, 1] */
    float navigation[16];     /* CAVE space to world space */
} cavelight_input;

/* One screen for one eye, in draw. The G-buffer's framebuffer is bound with its viewport,
 * depth test (GL_LESS) and depth writes on. */
typedef struct cavelight_draw {
    const char *screen;       /* the config's screen name */
    int eye;                  /* -1 left, 0 centre (mono), +1 right */
    int width, height;        /* pixels */
    float view[16], projection[16], view_projection[16]; /* world space to clip space */
    float eye_position[3];    /* world space */
    unsigned framebuffer;     /* GL name of the G-buffer (bound) */
    unsigned depth_texture;   /* GL name of its depth (GL_DEPTH_COMPONENT32F) */
} cavelight_draw;

typedef struct cavelight_app_desc {
    int version;              /* CAVELIGHT_APP_VERSION (0: the current one) */
    const char *name;         /* for messages; NULL: the file's name */
    void *user;               /* cavelight_app_user() */
    uint32_t buttons;         /* buttons it takes (bits 1 << CAVELIGHT_BUTTON_*): they reach its
                                 update only, not the master's interaction layouts */
    void (*init)(cavelight_app *app);
    void (*update)(cavelight_app *app, const cavelight_input *in);
    void (*frame)(cavelight_app *app);
    void (*draw)(cavelight_app *app, const cavelight_draw *d);
    void (*shutdown)(cavelight_app *app);
} cavelight_app_desc;

/* The one symbol an application defines. */
CAVELIGHT_API cavelight_app_desc cavelight_app_main(void);

CAVELIGHT_API cavelight_role cavelight_app_role(const cavelight_app *app);
CAVELIGHT_API void *cavelight_app_user(const cavelight_app *app);
/* "master", or the render node's name in the cluster config. */
CAVELIGHT_API const char *cavelight_app_process(const cavelight_app *app);
/* The last refusal's line ("" when none). */
CAVELIGHT_API const char *cavelight_last_error(const cavelight_app *app);

/* ---- keys: register in init, set in update (master), read anywhere ----------------- */

typedef int cavelight_key; /* >= 0; -1 when refused */

CAVELIGHT_API cavelight_key cavelight_key_number(cavelight_app *app, const char *name, double initial);
/* n floats, 2 to 4; initial NULL: zeros. */
CAVELIGHT_API cavelight_key cavelight_key_vector(cavelight_app *app, const char *name, int n, const float *initial);
/* initial NULL: identity. */
CAVELIGHT_API cavelight_key cavelight_key_matrix(cavelight_app *app, const char *name, const float *initial);
/* At most capacity bytes (a string: UTF-8 without NUL, the terminator not counted),
 * 1 to 4096; every string and blob together 16 KiB at most. They start empty. */
CAVELIGHT_API cavelight_key cavelight_key_string(cavelight_app *app, const char *name, size_t capacity);
CAVELIGHT_API cavelight_key cavelight_key_blob(cavelight_app *app, const char *name, size_t capacity);
/* A key registered by this application, or -1. */
CAVELIGHT_API cavelight_key cavelight_key_find(const cavelight_app *app, const char *name);

/* Setters return 0, or -1 (nothing changed). A value equal to the current one sends
 * nothing. */
CAVELIGHT_API int cavelight_set_number(cavelight_app *app, cavelight_key key, double v);
CAVELIGHT_API int cavelight_set_vector(cavelight_app *app, cavelight_key key, int n, const float *v);
CAVELIGHT_API int cavelight_set_matrix(cavelight_app *app, cavelight_key key, const float *m);
CAVELIGHT_API int cavelight_set_string(cavelight_app *app, cavelight_key key, const char *s);
CAVELIGHT_API int cavelight_set_blob(cavelight_app *app, cavelight_key key, const void *data, size_t len);

/* The frame's values (on the master: as set so far). A bad key or type gives 0 / -1 /
 * NULL. */
CAVELIGHT_API double cavelight_get_number(cavelight_app *app, cavelight_key key);
CAVELIGHT_API int cavelight_get_vector(cavelight_app *app, cavelight_key key, int n, float *out);
CAVELIGHT_API int cavelight_get_matrix(cavelight_app *app, cavelight_key key, float *out);
/* NUL-terminated, valid until the next frame. */
CAVELIGHT_API const char *cavelight_get_string(cavelight_app *app, cavelight_key key);
CAVELIGHT_API const void *cavelight_get_blob(cavelight_app *app, cavelight_key key, size_t *len);

/* ---- the scene's objects ----------------------------------------------------------- */

CAVELIGHT_API int cavelight_object_count(const cavelight_app *app);
/* The object named name, or -1. */
CAVELIGHT_API int cavelight_object_find(const cavelight_app *app, const char *name);
CAVELIGHT_API const char *cavelight_object_name(const cavelight_app *app, int object);
/* Its offset (identity: as loaded) and visibility; setting them: update only. */
CAVELIGHT_API int cavelight_object_set_offset(cavelight_app *app, int object, const float *m);
CAVELIGHT_API int cavelight_object_set_visible(cavelight_app *app, int object, int visible);
CAVELIGHT_API int cavelight_object_offset(cavelight_app *app, int object, float *out);
CAVELIGHT_API int cavelight_object_visible(cavelight_app *app, int object);
/* Where its triangles are now: its model matrix (its parents' offsets times its own). */
CAVELIGHT_API int cavelight_object_model(cavelight_app *app, int object, float *out);
/* The box of its own triangles as loaded, world space. */
CAVELIGHT_API int cavelight_object_bounds(const cavelight_app *app, int object, float *lo, float *hi);

/* ---- drawing (draw only) ----------------------------------------------------------- */

typedef struct cavelight_vertex {
    float position[3];        /* world space */
    float normal[3];          /* zero: facing the eye (points, lines) */
    float color[3];           /* linear albedo, 0..1 */
} cavelight_vertex;

/* count points of size pixels, or count/2 line segments, into the G-buffer (lit like the
 * scene, roughness 0.8). -1 outside draw. */
CAVELIGHT_API int cavelight_draw_points(cavelight_app *app, const cavelight_draw *d, const cavelight_vertex *v,
                          int count, float size);
CAVELIGHT_API int cavelight_draw_lines(cavelight_app *app, const cavelight_draw *d, const cavelight_vertex *v,
                         int count);
/* A GL 4.3 core function of the node's context ("glDrawArrays"), or NULL (the master, or
 * no such function). Own drawing writes the G-buffer's four outputs: location 0 world
 * position (w 1), 1 unit normal (w roughness), 2 albedo (w 1), 3 emitted radiance (w 1). */
CAVELIGHT_API void *cavelight_gl_proc(cavelight_app *app, const char *name);

/* ---- matrices ---------------------------------------------------------------------- */

CAVELIGHT_API void cavelight_mat4_identity(float *m);
CAVELIGHT_API void cavelight_mat4_translation(float *m, float x, float y, float z);
/* A rotation by radians about the axis (x, y, z). */
CAVELIGHT_API void cavelight_mat4_rotation(float *m, float radians, float x, float y, float z);
/* out = the inverse of the affine m (rotation, scale, translation); -1 when singular. */
CAVELIGHT_API int cavelight_mat4_inverse(const float *m, float *out);
/* out = a * b (out may be a or b). */
CAVELIGHT_API void cavelight_mat4_mul(const float *a, const float *b, float *out);
/* out = m applied to the point p (w 1). */
CAVELIGHT_API void cavelight_mat4_point(const float *m, const float *p, float *out);

#ifdef __cplusplus
}
#endif

#endif
