/* renderer_hud: the wand-referenced HUD (paper appendix, User Interaction 3) as small
 * meshes made in code, drawn in world space into the final image of every eye pass,
 * depth-tested against the scene's G-buffer depth. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mat4.h"
#include "base/xalloc.h"
#include "base/vec3.h"
#include "renderer_hud.h"
#include "gl/gltools.h"

enum { RENDERER_HUD_BOX, RENDERER_HUD_CONE, RENDERER_HUD_TORUS, RENDERER_HUD_MESHES };

/* One program, three meshes in one buffer. */
struct renderer_hud {
    const gl_functions *gl;
    GLuint prog_hud, hud_vao, hud_vbo;
    GLint hud_first[RENDERER_HUD_MESHES];
    GLsizei hud_count[RENDERER_HUD_MESHES];
    GLint hud_loc_model, hud_loc_view_projection, hud_loc_color, hud_loc_eye, hud_loc_gamma;
};

/* Panel layout in the wand's frame, metres (see renderer_hud.h). */
static const float INDICATOR_X = -0.07f;
static const float INDICATOR_Y[HUD_INDICATOR_COUNT] = {0.045f, 0.0f, -0.045f};
static const float LETTER_X = 0.03f, LETTER_SIZE = 0.018f, STROKE = 0.003f;
static const float BAR_X = 0.05f, BAR_THICK = 0.014f, BAR_DEPTH = 0.008f;
static const float BAR_Y[HUD_BAR_COUNT] = {0.045f, 0.015f, -0.015f, -0.045f};
static const float TRACK_GREY = 0.3f;
static const float PANEL_MIN[3] = {-0.095f, -0.07f, -RENDERER_HUD_DISTANCE - 0.02f};
static const float PANEL_MAX[3] = {0.185f, 0.07f, -RENDERER_HUD_DISTANCE + 0.02f};

enum { SEGMENTS = 24, TORUS_RINGS = 8 };
static const float PI = 3.14159265f;

/* ---- small maths -------------------------------------------------------------------- */

/* Local matrix from three (scaled) axis columns and a translation. */
static void columns(const float x[3], const float y[3], const float z[3], const float t[3],
                    float out[16])
{
    const float *col[4] = {x, y, z, t};
    for (int c = 0; c < 4; c++) {
        for (int r = 0; r < 3; r++)
            out[c * 4 + r] = col[c][r];
        out[c * 4 + 3] = c == 3 ? 1.0f : 0.0f;
    }
}

/* ---- layout ------------------------------------------------------------------------- */

void renderer_hud_layout(const hud *h, renderer_hud_places *out)
{
    const float *w = h->wand_world;
    const float z = -RENDERER_HUD_DISTANCE;
    for (int i = 0; i < HUD_INDICATOR_COUNT; i++)
        mat4_transform_point(w, (const float[3]){INDICATOR_X, INDICATOR_Y[i], z}, out->indicator[i]);
    for (int i = 0; i < HUD_BAR_COUNT; i++)
        mat4_transform_point(w, (const float[3]){BAR_X, BAR_Y[i], z}, out->bar_start[i]);
    for (int r = 0; r < 3; r++)
        out->bar_axis[r] = w[r];
    vec3_normalize(out->bar_axis);
    for (int k = 0; k < 8; k++) {
        const float p[3] = {k & 1 ? PANEL_MAX[0] : PANEL_MIN[0], k & 2 ? PANEL_MAX[1] : PANEL_MIN[1],
                            k & 4 ? PANEL_MAX[2] : PANEL_MIN[2]};
        mat4_transform_point(w, p, out->panel_corner[k]);
    }
}

void renderer_hud_wand_in_front(const float view[16], float wand[16])
{
    /* eye-to-world = inverse of the rigid view: rotation transposed, eye position. */
    float inv[16];
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            inv[c * 4 + r] = view[r * 4 + c];
    for (int r = 0; r < 3; r++)
        inv[12 + r] = -(inv[r] * view[12] + inv[4 + r] * view[13] + inv[8 + r] * view[14]);
    inv[3] = inv[7] = inv[11] = 0;
    inv[15] = 1;
    /* Wand origin placed so that the panel's centre lands on the view axis. */
    float centre_x = 0.5f * (PANEL_MIN[0] + PANEL_MAX[0]);
    const float x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, zc[3] = {0, 0, 1};
    const float t[3] = {-centre_x, 0, -0.42f + RENDERER_HUD_DISTANCE};
    float local[16];
    columns(x, y, zc, t, local);
    mat4_mul(inv, local, wand);
}

/* ---- meshes ------------------------------------------------------------------------- */

typedef struct mesh_builder {
    float *v;    /* position + normal per vertex */
    int count, capacity;
} mesh_builder;

static void vertex(mesh_builder *b, const float p[3], const float n[3])
{
    if (b->count >= b->capacity)
        return;
    float *d = b->v + (size_t)b->count++ * 6;
    memcpy(d, p, 3 * sizeof(float));
    memcpy(d + 3, n, 3 * sizeof(float));
}

static void triangle(mesh_builder *b, const float a[3], const float na[3], const float c[3],
                     const float nc[3], const float d[3], const float nd[3])
{
    vertex(b, a, na);
    vertex(b, c, nc);
    vertex(b, d, nd);
}

/* Unit cube centred on the origin. */
static void build_box(mesh_builder *b)
{
    for (int axis = 0; axis < 3; axis++)
        for (int side = -1; side <= 1; side += 2) {
            float n[3] = {0, 0, 0};
            n[axis] = (float)side;
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            float q[4][3];
            for (int k = 0; k < 4; k++) {
                q[k][axis] = 0.5f * side;
                q[k][u] = (k == 1 || k == 2) ? 0.5f : -0.5f;
                q[k][v] = (k >= 2) ? 0.5f : -0.5f;
            }
            triangle(b, q[0], n, q[1], n, q[2], n);
            triangle(b, q[0], n, q[2], n, q[3], n);
        }
}

/* Apex at the origin, axis +Z, base disc of radius 1 at z = 1. */
static void build_cone(mesh_builder *b)
{
    const float apex[3] = {0, 0, 0}, centre[3] = {0, 0, 1}, out[3] = {0, 0, 1};
    const float k = 1.0f / sqrtf(2.0f); /* slant normal of a 45-degree unit cone */
    for (int i = 0; i < SEGMENTS; i++) {
        float a0 = 2.0f * PI * i / SEGMENTS, a1 = 2.0f * PI * (i + 1) / SEGMENTS;
        float p0[3] = {cosf(a0), sinf(a0), 1}, p1[3] = {cosf(a1), sinf(a1), 1};
        float n0[3] = {k * p0[0], k * p0[1], -k}, n1[3] = {k * p1[0], k * p1[1], -k};
        float am = 0.5f * (a0 + a1);
        float nm[3] = {k * cosf(am), k * sinf(am), -k};
        triangle(b, apex, nm, p0, n0, p1, n1);
        triangle(b, centre, out, p1, out, p0, out);
    }
}

/* Major radius 1, minor radius 0.3, around the Z axis. */
static void build_torus(mesh_builder *b)
{
    const float minor = 0.3f;
    for (int i = 0; i < SEGMENTS; i++)
        for (int j = 0; j < TORUS_RINGS; j++) {
            float p[4][3], n[4][3];
            for (int k = 0; k < 4; k++) {
                int ii = i + (k == 1 || k == 2), jj = j + (k >= 2);
                float u = 2.0f * PI * ii / SEGMENTS;
                float v = 2.0f * PI * jj / TORUS_RINGS;
                n[k][0] = cosf(v) * cosf(u);
                n[k][1] = cosf(v) * sinf(u);
                n[k][2] = sinf(v);
                p[k][0] = cosf(u) + minor * n[k][0];
                p[k][1] = sinf(u) + minor * n[k][1];
                p[k][2] = minor * n[k][2];
            }
            triangle(b, p[0], n[0], p[1], n[1], p[2], n[2]);
            triangle(b, p[0], n[0], p[2], n[2], p[3], n[3]);
        }
}

renderer_hud *renderer_hud_create(const gl_functions *gl, char *err, size_t errlen)
{
    renderer_hud *r = xcalloc(1, sizeof *r);
    r->gl = gl;
    if (!(r->prog_hud = gltools_program(gl, "hud.vert", "hud.frag", NULL, NULL, NULL, err, errlen))) {
        renderer_hud_destroy(r);
        return NULL;
    }
    r->hud_loc_model = gl->GetUniformLocation(r->prog_hud, "u_model");
    r->hud_loc_view_projection = gl->GetUniformLocation(r->prog_hud, "u_view_projection");
    r->hud_loc_color = gl->GetUniformLocation(r->prog_hud, "u_color");
    r->hud_loc_eye = gl->GetUniformLocation(r->prog_hud, "u_eye");
    r->hud_loc_gamma = gl->GetUniformLocation(r->prog_hud, "u_encoding_gamma");

    mesh_builder b = {.capacity = 36 + SEGMENTS * 6 + SEGMENTS * TORUS_RINGS * 6};
    b.v = xmalloc((size_t)b.capacity * 6 * sizeof(float));
    void (*build[RENDERER_HUD_MESHES])(mesh_builder *) = {build_box, build_cone, build_torus};
    for (int m = 0; m < RENDERER_HUD_MESHES; m++) {
        r->hud_first[m] = b.count;
        build[m](&b);
        r->hud_count[m] = b.count - r->hud_first[m];
    }
    gl->GenVertexArrays(1, &r->hud_vao);
    gl->BindVertexArray(r->hud_vao);
    gl->GenBuffers(1, &r->hud_vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->hud_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)b.count * 6 * sizeof(float)), b.v,
                   GL_STATIC_DRAW);
    for (GLuint a = 0; a < 2; a++) {
        gl->EnableVertexAttribArray(a);
        gl->VertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                                (const void *)(uintptr_t)(a * 3 * sizeof(float)));
    }
    gl->BindVertexArray(0);
    free(b.v);
    return r;
}

void renderer_hud_destroy(renderer_hud *r)
{
    if (!r)
        return;
    const gl_functions *gl = r->gl;
    if (r->prog_hud)
        gl->DeleteProgram(r->prog_hud);
    if (r->hud_vbo)
        gl->DeleteBuffers(1, &r->hud_vbo);
    if (r->hud_vao)
        gl->DeleteVertexArrays(1, &r->hud_vao);
    free(r);
}

/* ---- drawing ------------------------------------------------------------------------ */

static void draw(renderer_hud *r, int mesh, const float model[16], const float color[3])
{
    const gl_functions *gl = r->gl;
    gl->UniformMatrix4fv(r->hud_loc_model, 1, GL_FALSE, model);
    gl->Uniform3fv(r->hud_loc_color, 1, color);
    gl->DrawArrays(GL_TRIANGLES, r->hud_first[mesh], r->hud_count[mesh]);
}

/* A mesh placed in the wand's frame: model = wand_world * local. */
static void draw_local(renderer_hud *r, const hud *h, int mesh, const float x[3], const float y[3],
                       const float z[3], const float t[3], const float color[3])
{
    float local[16], model[16];
    columns(x, y, z, t, local);
    mat4_mul(h->wand_world, local, model);
    draw(r, mesh, model, color);
}

/* Axis-aligned box in the wand's frame. */
static void draw_box(renderer_hud *r, const hud *h, const float centre[3], const float size[3],
                     const float color[3])
{
    draw_local(r, h, RENDERER_HUD_BOX, (const float[3]){size[0], 0, 0},
               (const float[3]){0, size[1], 0}, (const float[3]){0, 0, size[2]}, centre, color);
}

/* A stroke of a letter, from a to b in the panel plane (wand x, y at depth z). */
static void draw_stroke(renderer_hud *r, const hud *h, const float a[2], const float b[2], float z,
                        const float color[3])
{
    float d[2] = {b[0] - a[0], b[1] - a[1]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1]);
    float u[2] = {d[0] / len, d[1] / len};
    float ext = len + STROKE; /* overlap at the joints */
    draw_local(r, h, RENDERER_HUD_BOX, (const float[3]){u[0] * ext, u[1] * ext, 0},
               (const float[3]){-u[1] * STROKE, u[0] * STROKE, 0}, (const float[3]){0, 0, STROKE},
               (const float[3]){0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), z}, color);
}

/* Letters as strokes on a 2 x 2 grid (x right, y up). */
typedef struct letter_strokes {
    char letter;
    int count;
    float seg[5][4];
} letter_strokes;

static const letter_strokes LETTERS[HUD_BAR_COUNT] = {
    {'A', 3, {{0, 0, 1, 2}, {1, 2, 2, 0}, {0.5f, 1, 1.5f, 1}}},
    {'S', 5, {{2, 2, 0, 2}, {0, 2, 0, 1}, {0, 1, 2, 1}, {2, 1, 2, 0}, {2, 0, 0, 0}}},
    {'I', 1, {{1, 0, 1, 2}}},
    {'P', 4, {{0, 0, 0, 2}, {0, 2, 2, 2}, {2, 2, 2, 1}, {2, 1, 0, 1}}},
};

static void draw_letter(renderer_hud *r, const hud *h, char letter, float cx, float cy, float z,
                        const float color[3])
{
    float unit = 0.5f * LETTER_SIZE;
    for (int i = 0; i < HUD_BAR_COUNT; i++) {
        if (LETTERS[i].letter != letter)
            continue;
        for (int s = 0; s < LETTERS[i].count; s++) {
            const float *g = LETTERS[i].seg[s];
            float a[2] = {cx + (g[0] - 1) * unit, cy + (g[1] - 1) * unit};
            float b[2] = {cx + (g[2] - 1) * unit, cy + (g[3] - 1) * unit};
            draw_stroke(r, h, a, b, z, color);
        }
    }
}

/* Cone with its apex at apex, opening along axis (unit) by half angle a, length len:
 * placed through the world matrix base (wand_world, or identity for world space). */
static void draw_cone(renderer_hud *r, const float base[16], const float apex[3],
                      const float axis[3], float angle, float len, const float color[3])
{
    float u[3], helper[3] = {1, 0, 0};
    if (fabsf(axis[0]) > 0.9f)
        helper[0] = 0, helper[1] = 1;
    vec3_cross(axis, helper, u);
    vec3_normalize(u);
    float v[3];
    vec3_cross(axis, u, v);
    float rad = len * tanf(angle);
    float x[3], y[3], z[3], local[16], model[16];
    for (int k = 0; k < 3; k++) {
        x[k] = u[k] * rad;
        y[k] = v[k] * rad;
        z[k] = axis[k] * len;
    }
    columns(x, y, z, apex, local);
    mat4_mul(base, local, model);
    draw(r, RENDERER_HUD_CONE, model, color);
}

static float clampf(float x, float lo, float hi) { return x < lo ? lo : x > hi ? hi : x; }

/* Light 0 at its real pose, in world space, RENDERER_HUD_LIGHT_MARKER long: a spot's cone
 * (opened by angle), a point light's star of three bars (light goes every way), a
 * directional light's arrow along its direction (where it comes from does not matter). */
static void draw_light_marker(renderer_hud *r, const hud *h, float angle, const float color[3])
{
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const float len = RENDERER_HUD_LIGHT_MARKER, thick = 0.12f * RENDERER_HUD_LIGHT_MARKER;
    const float *p = h->light_position;
    float axis[3], local[16];
    memcpy(axis, h->light_direction, sizeof axis);
    vec3_normalize(axis);
    if (h->light_type == SCENE_LIGHT_POINT) {
        for (int a = 0; a < 3; a++) {
            float c[3][3] = {{thick, 0, 0}, {0, thick, 0}, {0, 0, thick}};
            c[a][a] = len;
            columns(c[0], c[1], c[2], p, local);
            draw(r, RENDERER_HUD_BOX, local, color);
        }
    } else if (h->light_type == SCENE_LIGHT_DIRECTIONAL) {
        float u[3], v[3], helper[3] = {1, 0, 0}, mid[3], apex[3];
        if (fabsf(axis[0]) > 0.9f)
            helper[0] = 0, helper[1] = 1;
        vec3_cross(axis, helper, u);
        vec3_normalize(u);
        vec3_cross(axis, u, v);
        float x[3], y[3], z[3];
        for (int k = 0; k < 3; k++) {
            x[k] = u[k] * thick;
            y[k] = v[k] * thick;
            z[k] = axis[k] * 0.7f * len;
            mid[k] = p[k] + axis[k] * 0.35f * len;
            apex[k] = p[k] + axis[k] * len;
        }
        columns(x, y, z, mid, local);
        draw(r, RENDERER_HUD_BOX, local, color);
        const float back[3] = {-axis[0], -axis[1], -axis[2]};
        draw_cone(r, identity, apex, back, 0.4f, 0.3f * len, color);
    } else {
        draw_cone(r, identity, p, axis, angle, len, color);
    }
}

void renderer_hud_draw(renderer_hud *r, const frame_params *p, int cells,
                       const float view_projection[16], const float eye[3], float encoding_gamma)
{
    hud h;
    hud_describe(p, cells, &h);
    if (!h.visible)
        return;
    const gl_functions *gl = r->gl;
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    gl->UseProgram(r->prog_hud);
    gl->UniformMatrix4fv(r->hud_loc_view_projection, 1, GL_FALSE, view_projection);
    gl->Uniform3fv(r->hud_loc_eye, 1, eye);
    gl->Uniform1f(r->hud_loc_gamma, encoding_gamma);
    gl->BindVertexArray(r->hud_vao);

    const float z = -RENDERER_HUD_DISTANCE;
    /* Arrow (navigation): a shaft and a head pointing up the panel. */
    const hud_indicator *ind = h.indicators;
    float cx = INDICATOR_X, cy = INDICATOR_Y[HUD_SHAPE_ARROW];
    draw_box(r, &h, (const float[3]){cx, cy - 0.006f, z}, (const float[3]){0.007f, 0.024f, 0.007f},
             ind[HUD_SHAPE_ARROW].color);
    draw_cone(r, h.wand_world, (const float[3]){cx, cy + 0.02f, z}, (const float[3]){0, -1, 0},
              atanf(0.011f / 0.016f), 0.016f, ind[HUD_SHAPE_ARROW].color);
    /* Cone (lighting): opened by the spot's angle, shortened so that it fits its slot. */
    int spot = h.has_light && h.light_type == SCENE_LIGHT_SPOT;
    float angle = clampf(spot ? h.light_angle : 0.5f, 0.05f, 1.45f);
    float len = fminf(0.036f, 0.02f / tanf(angle));
    cy = INDICATOR_Y[HUD_SHAPE_CONE];
    draw_cone(r, h.wand_world, (const float[3]){cx, cy + 0.5f * len, z}, (const float[3]){0, -1, 0},
              angle, len, ind[HUD_SHAPE_CONE].color);
    /* Torus (renderer settings), facing the user. */
    const float s = 0.013f;
    draw_local(r, &h, RENDERER_HUD_TORUS, (const float[3]){s, 0, 0}, (const float[3]){0, s, 0},
               (const float[3]){0, 0, s}, (const float[3]){cx, INDICATOR_Y[HUD_SHAPE_TORUS], z},
               ind[HUD_SHAPE_TORUS].color);
    if (h.has_light)
        draw_light_marker(r, &h, angle, ind[HUD_SHAPE_CONE].color);
    /* Bars: a dark track of full length inside a bar as long as the value. */
    const float track[3] = {TRACK_GREY, TRACK_GREY, TRACK_GREY};
    for (int i = 0; i < HUD_BAR_COUNT; i++) {
        const hud_bar *bar = &h.bars[i];
        float y = BAR_Y[i];
        draw_box(r, &h, (const float[3]){BAR_X + 0.5f * RENDERER_HUD_BAR_LENGTH, y, z},
                 (const float[3]){RENDERER_HUD_BAR_LENGTH, 0.3f * BAR_THICK, 0.3f * BAR_DEPTH},
                 track);
        float l = bar->value * RENDERER_HUD_BAR_LENGTH;
        if (l > 0)
            draw_box(r, &h, (const float[3]){BAR_X + 0.5f * l, y, z},
                     (const float[3]){l, BAR_THICK, BAR_DEPTH}, bar->color);
        draw_letter(r, &h, bar->letter, LETTER_X, y, z, bar->color);
    }
    gl->BindVertexArray(0);
    gl->Disable(GL_DEPTH_TEST);
}
