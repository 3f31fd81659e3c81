/* gi_vpl: the vpl method (gi_vpl.h). Host: RSM readback, candidates, selection, checksum.
 * GL: the VPLs as a 3 x VPL_COUNT_MAX float texture, their shadow maps as tiles of a depth
 * array texture (shaders/vpl_shadow.frag writes distance / far), bound for shade.frag. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/vec3.h"
#include "base/xalloc.h"
#include "gi/vpl/vpl_cluster.h"
#include "gi/vpl/vpl_select.h"
#include "gi/vpl_source.h"
#include "gi/vpl/gi_vpl.h"
#include "gi/vpl/vpl_interleave.h"
#include "gi/vpl/vpl_ism.h"
#include "gl/gltools.h"
#include "gi/gi_reuse.h"
#include "gi/view_samples.h"

enum { VPL_ATLAS_SIDE = 2048 };
/* The view rule evaluates the view term of about this many candidates (evenly spaced
 * among the texels and among the emitters, vpl_view_term()), so its cost is fixed whatever
 * the RSM size: every texel of a 256^2 map would take 65536 x VPL_VIEW_SAMPLES kernel
 * evaluations per light view. */
enum { VIEW_TERM_EVALS = 4096 };
/* Rays of the view rule: the high-res RSM paper found 256 view samples enough. */
enum { VPL_VIEW_SAMPLES = 256 };
/* Texture units of its shading snippet's samplers, from gi_eye.first_unit on. */
enum { UNIT_VPLS = 0, UNIT_SHADOW, UNIT_CLUSTERS, UNIT_LISTS, UNIT_ISM, UNIT_IRRADIANCE };

/* Cube faces +x, -x, +y, -y, +z, -z (face = 2 axis + negative): axis, right, up. The shader
 * takes them as uniforms, so this table is the only one. */
static const float FACE_AXIS[VPL_FACES][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                              {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const float FACE_RIGHT[VPL_FACES][3] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0},
                                               {1, 0, 0}, {1, 0, 0}, {-1, 0, 0}};
static const float FACE_UP[VPL_FACES][3] = {{0, 1, 0}, {0, 1, 0}, {0, 0, -1},
                                            {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};

typedef struct gi_vpl {
    const gl_functions *gl;
    const scene *scene;
    gi_rsm_reader reader;    /* one RSM layer read back */
    int rsm_size;
    vpl_settings settings;   /* the last frame's */
    float head_to_eye[3];    /* the viewer (frame_view_head_centre()) */
    gi_reuse_state reuse;    /* the last frame's parameters */
    vpl *candidates;         /* this frame's: RSM texels, then the emitters */
    double *cdf;             /* vpl_select()'s scratch */
    double *view;            /* the view rule's view term per candidate */
    size_t capacity;
    view_samples *viewer;    /* the view rule's rays (view_samples.h); only with that rule */
    vpl *emitters;           /* as candidates: at their centroids */
    vpl_emitter *emitter_shape; /* their triangles */
    size_t emitter_count;
    vpl chosen[VPL_COUNT_MAX];
    size_t chosen_index[VPL_COUNT_MAX]; /* each slot's candidate */
    int count;
    uint64_t checksum;
    float near, far;         /* shadow maps: clip plane, distance stored as depth 1 */

    GLuint prog_shadow;
    struct { GLint view_projection, position, far; } loc;
    GLuint vpl_tex;          /* 3 x VPL_COUNT_MAX RGBA32F: position + area, normal, flux */
    float upload[VPL_COUNT_MAX * 12];
    GLuint shadow_tex, shadow_fbo;
    int face, tiles, layers; /* face side, tiles per atlas side, layers allocated */
    vpl_ism *ism;            /* imperfect maps instead (vpl_settings.visibility) */
    int have_maps;           /* this frame's VPLs have their maps */
    vpl_interleave *interleave; /* vpl_settings.interleave > 0 */

    /* Light assignment (vpl_cluster.h) */
    float scene_area;        /* m^2 of all triangles: the cut's even share */
    float radius[VPL_COUNT_MAX];
    vpl_grid grid;           /* the lists' grid: a view's own, or its screen's */
    int grid_valid;          /* 0: no grid (orthographic view): every VPL */
    vpl_clusters lists;
    frame_view screen_views[2]; /* the screen announced with its enclosing grid */
    int screen_count;
    int lists_frame;         /* frame the lists were assigned for (the VPLs change) */
    int frame_number;
    GLuint cluster_tex, list_tex; /* the lists (eye_bind) */
    int cluster_rows, list_rows;  /* rows of LIST_ROW texels they hold */
    double select_ms, shadow_ms, assign_ms; /* the last frame's stages; the last assignment */
    gpu_timer *timer;        /* the renderer's: the stages' GPU time */
    size_t assignments;      /* its (VPL, cluster) pairs */
} gi_vpl;

static void release_shadow(gi_vpl *v)
{
    if (v->shadow_tex)
        v->gl->DeleteTextures(1, &v->shadow_tex);
    v->shadow_tex = 0;
    v->layers = 0;
}

/* Room for n VPLs' faces; the atlas is rebuilt when the face size changes or it is short
 * of layers. Returns -1 (no shadow maps: the frame's VPLs are then left out) when the FBO
 * is not complete. */
static int reserve_shadow(gi_vpl *v, int n)
{
    const gl_functions *gl = v->gl;
    int face = vpl_shadow_face(n);
    int tiles_needed = (int)ceil(sqrt((double)VPL_FACES * n));
    int tiles = VPL_ATLAS_SIDE / face < tiles_needed ? VPL_ATLAS_SIDE / face : tiles_needed;
    int layers = (VPL_FACES * n + tiles * tiles - 1) / (tiles * tiles);
    if (face == v->face && tiles == v->tiles && layers <= v->layers)
        return 0;
    release_shadow(v);
    v->shadow_tex = gltools_texture_array(gl, GL_DEPTH_COMPONENT16, face * tiles, layers);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, v->shadow_tex);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl->BindFramebuffer(GL_FRAMEBUFFER, v->shadow_fbo);
    gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, v->shadow_tex, 0, 0);
    const GLenum none = GL_NONE;
    gl->DrawBuffers(1, &none);
    gl->ReadBuffer(GL_NONE);
    char err[160];
    int bad = gltools_fbo_complete(gl, "VPL shadow", err, sizeof err);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (bad) {
        fprintf(stderr, "cavelight-node: %s: indirect light left out\n", err);
        release_shadow(v);
        v->face = v->tiles = 0;
        return -1;
    }
    v->face = face;
    v->tiles = tiles;
    v->layers = layers;
    return 0;
}

static void release(gi_vpl *v)
{
    const gl_functions *gl = v->gl;
    release_shadow(v);
    vpl_ism_destroy(v->ism);
    vpl_interleave_destroy(v->interleave);
    if (v->shadow_fbo)
        gl->DeleteFramebuffers(1, &v->shadow_fbo);
    if (v->vpl_tex)
        gl->DeleteTextures(1, &v->vpl_tex);
    if (v->cluster_tex)
        gl->DeleteTextures(1, &v->cluster_tex);
    if (v->list_tex)
        gl->DeleteTextures(1, &v->list_tex);
    vpl_clusters_free(&v->lists);
    if (v->prog_shadow)
        gl->DeleteProgram(v->prog_shadow);
    gi_rsm_reader_free(&v->reader);
    free(v->candidates);
    free(v->cdf);
    free(v->view);
    view_samples_destroy(v->viewer);
    free(v->emitters);
    free(v->emitter_shape);
}

static int init(gi_vpl *v, char *err, size_t errlen)
{
    const gl_functions *gl = v->gl;
    const scene *s = v->scene;
    v->emitter_count = vpl_emitters(s, NULL);
    /* not xalloc: the scene's emitters (a file's): refused in err */
    v->emitters = malloc((v->emitter_count ? v->emitter_count : 1) * sizeof *v->emitters);
    vpl_emitter *raw = v->emitter_shape =
        malloc((v->emitter_count ? v->emitter_count : 1) * sizeof *raw);
    if (!v->emitters || !raw) {
        snprintf(err, errlen, "renderer: out of memory for %zu emitters", v->emitter_count);
        return -1;
    }
    vpl_emitters(s, raw);
    for (size_t i = 0; i < v->emitter_count; i++)
        v->emitters[i] = vpl_from_emitter(&raw[i]);
    for (size_t t = 0; t < s->triangle_count; t++)
        v->scene_area += vec3_triangle_area(s->positions + 9 * t);
    float diagonal = scene_diagonal(s);
    v->near = diagonal / 1024.0f;
    v->far = diagonal * 1.01f; /* VPLs and receivers lie within the bounds */

    if (!(v->prog_shadow = gltools_program(gl, "scene.vert", "vpl/vpl_shadow.frag", NULL, NULL,
                                           NULL, err, errlen)))
        return -1;
    v->loc.view_projection = gl->GetUniformLocation(v->prog_shadow, "u_view_projection");
    v->loc.position = gl->GetUniformLocation(v->prog_shadow, "u_vpl_position");
    v->loc.far = gl->GetUniformLocation(v->prog_shadow, "u_far");
    v->vpl_tex = gltools_texture2d(gl, GL_RGBA32F, 3, VPL_COUNT_MAX, GL_NEAREST);
    gl->GenFramebuffers(1, &v->shadow_fbo);
    return 0;
}

/* Room for `need` candidates; 0, or -1 when memory is short. */
static int reserve_candidates(gi_vpl *v, size_t need)
{
    if (need <= v->capacity)
        return 0;
    /* not xalloc: the RSM size and VPL count (settings): -1 to the caller */
    vpl *c = realloc(v->candidates, need * sizeof *c);
    if (c)
        v->candidates = c;
    double *d = c ? realloc(v->cdf, need * sizeof *d) : NULL;
    if (d)
        v->cdf = d;
    double *w = d ? realloc(v->view, need * sizeof *w) : NULL;
    if (w)
        v->view = w;
    if (!c || !d || !w)
        return -1;
    v->capacity = need;
    return 0;
}

/* Every RSM layer's texels with flux, in layer then texel order, then the emitters;
 * *texels: how many of them are RSM texels. */
static size_t collect(gi_vpl *v, const gi_rsm *rsm, size_t *texels_out)
{
    size_t texels = (size_t)rsm->size * rsm->size;
    if (reserve_candidates(v, (size_t)rsm->layers * texels + v->emitter_count) != 0) {
        fprintf(stderr, "cavelight-node: out of memory for %d RSM layers of VPL candidates\n",
                rsm->layers);
        return *texels_out = 0;
    }
    size_t n = 0;
    for (int layer = 0; layer < rsm->layers; layer++) {
        const float *pos, *nrm, *flux;
        if (gi_rsm_read_layer(&v->reader, v->gl, rsm, layer, &pos, &nrm, &flux) != 0)
            break;
        n += vpl_from_rsm(pos, nrm, flux, rsm->size, v->candidates + n);
    }
    *texels_out = n;
    if (v->emitter_count)
        memcpy(v->candidates + n, v->emitters, v->emitter_count * sizeof *v->emitters);
    return n + v->emitter_count;
}

/* Column-major view-projection of cube face f seen from p: image x, y = right, up over
 * the depth along the axis (a 90 degree frustum), so shade.frag finds the texel from the
 * same table. */
static void face_view_projection(const gi_vpl *v, int f, const float p[3], float out[16])
{
    const float *a = FACE_AXIS[f], *r = FACE_RIGHT[f], *u = FACE_UP[f];
    float n = v->near, fa = v->far;
    float zz = -(fa + n) / (fa - n), zw = -2.0f * fa * n / (fa - n);
    float dr = r[0] * p[0] + r[1] * p[1] + r[2] * p[2];
    float du = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
    float da = a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
    /* view rows: r, u, -a (eye looks down -z); then the projection's z and w rows */
    for (int c = 0; c < 3; c++) {
        out[4 * c + 0] = r[c];
        out[4 * c + 1] = u[c];
        out[4 * c + 2] = -zz * a[c];
        out[4 * c + 3] = a[c];
    }
    out[12] = -dr;
    out[13] = -du;
    out[14] = zz * da + zw;
    out[15] = -da;
}

/* Face f lies wholly behind the VPL's surface: every direction of its frustum
 * (axis + s right + t up, |s|, |t| <= 1) has a non-positive cosine with the normal. */
static int face_behind(const float n[3], int f)
{
    float ca = 0, cr = 0, cu = 0;
    for (int k = 0; k < 3; k++) {
        ca += n[k] * FACE_AXIS[f][k];
        cr += n[k] * FACE_RIGHT[f][k];
        cu += n[k] * FACE_UP[f][k];
    }
    return ca + fabsf(cr) + fabsf(cu) <= 0.0f;
}

/* 0, or -1 when there is nothing to render or no room. */
static int render_shadows(gi_vpl *v, const scene_gl *mesh)
{
    const gl_functions *gl = v->gl;
    if (v->count == 0 || reserve_shadow(v, v->count) != 0)
        return -1;
    int per_layer = v->tiles * v->tiles, layer = -1;
    const float one = 1.0f;
    gl->UseProgram(v->prog_shadow);
    gl->BindFramebuffer(GL_FRAMEBUFFER, v->shadow_fbo);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    gl->Uniform1f(v->loc.far, v->far);
    for (int k = 0; k < VPL_FACES * v->count; k++) {
        const vpl *l = &v->chosen[k / VPL_FACES];
        int f = k % VPL_FACES;
        if (k / per_layer != layer) {
            layer = k / per_layer;
            gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, v->shadow_tex, 0,
                                        layer);
            gl->ClearBufferfv(GL_DEPTH, 0, &one);
        }
        if (face_behind(l->normal, f))
            continue;
        int tile = k % per_layer;
        gl->Viewport(tile % v->tiles * v->face, tile / v->tiles * v->face, v->face, v->face);
        float vp[16];
        face_view_projection(v, f, l->position, vp);
        gl->UniformMatrix4fv(v->loc.view_projection, 1, GL_FALSE, vp);
        gl->Uniform3fv(v->loc.position, 1, l->position);
        scene_gl_draw_geometry(mesh, v->prog_shadow); /* where the frame's objects are */
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return 0;
}

/* Each VPL's influence radius (vpl_cluster.h) for the kernel's area, and its square for
 * the shader (the largest float where there is no cut). */
static void upload_vpls(gi_vpl *v)
{
    for (int i = 0; i < v->count; i++) {
        const vpl *l = &v->chosen[i];
        float *t = v->upload + 12 * i;
        float area = v->settings.bound == VPL_BOUND_POINT ? 0.0f : l->area;
        float cut = v->settings.cut;
        v->radius[i] = vpl_influence_radius(area, v->scene_area, cut);
        memcpy(t, l->position, 3 * sizeof(float));
        t[3] = area;
        memcpy(t + 4, l->normal, 3 * sizeof(float));
        t[7] = cut > 0 ? v->radius[i] * v->radius[i] : FLT_MAX;
        memcpy(t + 8, l->flux, 3 * sizeof(float));
        t[11] = 0.0f;
    }
    if (v->count == 0)
        return;
    v->gl->BindTexture(GL_TEXTURE_2D, v->vpl_tex);
    v->gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    v->gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 3, v->count, GL_RGBA, GL_FLOAT, v->upload);
}

/* ---- the method --------------------------------------------------------------------- */

static void *create(const gi_desc *d, char *err, size_t errlen)
{
    gi_vpl *v = xcalloc(1, sizeof *v);
    v->gl = d->gl;
    v->scene = d->scene;
    v->rsm_size = d->rsm_size;
    vpl_settings_get(d->frame, &v->settings);
    v->reuse.never = d->no_reuse;
    v->timer = d->timer;
    memcpy(v->head_to_eye, d->head_to_eye, sizeof v->head_to_eye);
    int bad = init(v, err, errlen);
    if (!bad && v->settings.selection == VPL_SELECT_VIEW) /* Embree, loaded only for it */
        bad = !(v->viewer = view_samples_create(d->scene, VPL_VIEW_SAMPLES, err, errlen));
    if (!bad && v->settings.visibility != VPL_VISIBILITY_EXACT) {
        vpl_ism_desc id = {.gl = d->gl, .scene = d->scene, .far = v->far,
                           .size = v->settings.ism_size, .points = v->settings.ism_points,
                           .splat = v->settings.visibility == VPL_VISIBILITY_ISM_SPLAT};
        bad = !(v->ism = vpl_ism_create(&id, err, errlen));
    }
    if (!bad && v->settings.interleave > 0)
        bad = !(v->interleave = vpl_interleave_create(d->gl, v->settings.interleave, err, errlen));
    if (bad) {
        release(v);
        free(v);
        return NULL;
    }
    return v;
}

static void destroy(void *state)
{
    release(state);
    free(state);
}

/* The VPLs and their shadow maps depend on the lights, the medium and the VPL settings
 * only (gi_reuse_inputs_equal() and vpl_settings), and under the view rule on the
 * viewer: a frame that changes none of them keeps last frame's (the flux and regular
 * rules: a moving head's too). */
static int reuse(void *state, const frame_params *p)
{
    gi_vpl *v = state;
    vpl_settings now;
    vpl_settings_get(p, &now);
    float eye[3], before[3];
    view_samples_viewer(p, v->head_to_eye, eye);
    view_samples_viewer(&v->reuse.last, v->head_to_eye, before);
    int same = gi_reuse_unchanged(&v->reuse, p, &now, &v->settings, sizeof now,
                                  now.selection != VPL_SELECT_VIEW ||
                                  memcmp(eye, before, sizeof eye) == 0);
    if (same)
        v->select_ms = v->shadow_ms = 0;
    return same;
}

static uint64_t frame(void *state, const frame_params *p, const gi_rsm *rsm)
{
    gi_vpl *v = state;
    const vpl_settings *st = &v->settings; /* reuse() read them */
    double t0 = clock_now_ms();
    int h = gpu_timer_begin(v->timer, "select");
    size_t texels, candidates = collect(v, rsm, &texels);
    if (st->selection == VPL_SELECT_VIEW && candidates) {
        float eye[3];
        const float *samples;
        view_samples_viewer(p, v->head_to_eye, eye);
        int n = view_samples_cast(v->viewer, eye, VPL_VIEW_SAMPLES, &samples);
        size_t stride = (candidates + VIEW_TERM_EVALS - 1) / VIEW_TERM_EVALS;
        vpl_view_term(v->candidates, candidates, texels, samples, n, stride, v->view);
    }
    uint32_t seed = (uint32_t)st->seed;
    vpl_select_desc sd = {.candidates = v->candidates, .count = candidates, .texels = texels,
                          .rule = st->selection, .view = v->view, .n = st->count, .seed = seed};
    v->count = vpl_select(&sd, v->cdf, v->chosen, v->chosen_index);
    for (int i = 0; i < v->count; i++) /* an emitter's slot: a point of its triangle */
        if (v->chosen_index[i] >= texels)
            vpl_emitter_point(&v->emitter_shape[v->chosen_index[i] - texels],
                              vpl_slot_random(seed, i, 1), vpl_slot_random(seed, i, 2),
                              v->chosen[i].position);
    v->checksum = vpl_checksum(v->chosen, v->count);
    upload_vpls(v);
    v->frame_number++; /* lists of the last VPLs are stale */
    double t1 = clock_now_ms();
    gpu_timer_end(v->timer, h);
    h = gpu_timer_begin(v->timer, "shadow");
    if (v->ism)
        v->have_maps = vpl_ism_render(v->ism, v->vpl_tex, v->count) == 0;
    else
        v->have_maps = render_shadows(v, rsm->mesh) == 0;
    gpu_timer_end(v->timer, h);
    if (v->reuse.never) /* host ms of a measured frame; a node's frame never waits */
        v->gl->Finish();
    v->select_ms = t1 - t0;
    v->shadow_ms = clock_now_ms() - t1;
    return v->checksum;
}

/* Uploads the lists: cluster c's range first[c], first[c + 1] as R32UI texels (rows of
 * LIST_ROW), the VPL indices as R16UI texels. */
enum { LIST_ROW = 4096 };

static void upload_texture(const gl_functions *gl, GLuint *tex, int *rows_made, GLenum internal,
                           GLenum type, const void *data, size_t count, size_t size)
{
    size_t rows = (count + LIST_ROW - 1) / LIST_ROW, full = count / LIST_ROW;
    if (*tex == 0 || (size_t)*rows_made < rows) { /* grown by half again, at least 1 row */
        if (*tex)
            gl->DeleteTextures(1, tex);
        *rows_made = (int)(rows + rows / 2 + 1);
        *tex = gltools_texture2d(gl, internal, LIST_ROW, *rows_made, GL_NEAREST);
    }
    gl->BindTexture(GL_TEXTURE_2D, *tex);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (full)
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, LIST_ROW, (GLsizei)full, GL_RED_INTEGER, type,
                          data);
    if (count > full * LIST_ROW)
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, (GLint)full, (GLsizei)(count - full * LIST_ROW), 1,
                          GL_RED_INTEGER, type, (const char *)data + full * LIST_ROW * size);
}

/* Lists for grid g, timed (stats). */
static void assign(gi_vpl *v, const vpl_grid *g)
{
    double t0 = clock_now_ms();
    v->grid = *g;
    v->grid_valid = 1;
    vpl_clusters_assign(&v->lists, g, v->chosen, v->radius, v->count);
    size_t clusters = (size_t)vpl_grid_clusters(g);
    upload_texture(v->gl, &v->cluster_tex, &v->cluster_rows, GL_R32UI, GL_UNSIGNED_INT,
                   v->lists.first, clusters + 1, sizeof *v->lists.first);
    upload_texture(v->gl, &v->list_tex, &v->list_rows, GL_R16UI, GL_UNSIGNED_SHORT,
                   v->lists.index, v->lists.assigned, sizeof *v->lists.index);
    v->lists_frame = v->frame_number;
    v->assign_ms = clock_now_ms() - t0;
    v->assignments = v->lists.assigned;
}

static int slices(const gi_vpl *v)
{
    return v->settings.lights == VPL_LIGHTS_TILED ? 1 : VPL_CLUSTER_SLICES;
}

/* A screen's views: one grid enclosing them all, assigned once (enclosed clustering). */
static void screen(void *state, const frame_view *views, int n)
{
    gi_vpl *v = state;
    vpl_grid g;
    v->screen_count = 0;
    if (v->settings.lights == VPL_LIGHTS_ALL || v->count == 0 || n < 1 || n > 2 ||
        vpl_grid_enclosing(views, n, slices(v), &g) != 0)
        return;
    memcpy(v->screen_views, views, (size_t)n * sizeof *views);
    v->screen_count = n;
    assign(v, &g);
}

static int same_view(const frame_view *a, const frame_view *b)
{
    return memcmp(a->view, b->view, sizeof a->view) == 0 &&
           memcmp(a->projection, b->projection, sizeof a->projection) == 0 &&
           a->width == b->width && a->height == b->height;
}

/* The lists for this eye: its screen's when announced this frame, else its own grid's. */
static void eye_lists(gi_vpl *v, const frame_view *view)
{
    for (int i = 0; i < v->screen_count; i++)
        if (v->lists_frame == v->frame_number && same_view(view, &v->screen_views[i]))
            return;
    v->screen_count = 0;
    vpl_grid g;
    v->grid_valid = 0;
    if (v->settings.lights != VPL_LIGHTS_ALL && v->count > 0 &&
        vpl_grid_from_view(view, slices(v), &g) == 0)
        assign(v, &g);
}

/* A texture on unit first + u as prog's sampler name. */
static void bind_texture(const gl_functions *gl, GLuint prog, const char *name, GLenum target,
                         GLuint tex, int unit)
{
    gl->ActiveTexture((GLenum)(GL_TEXTURE0 + unit));
    gl->BindTexture(target, tex);
    gl->Uniform1i(gl->GetUniformLocation(prog, name), unit);
}

/* The gather's uniforms and textures on prog, the current program (the shading program,
 * or the de-interleaved gather); lists: it reads the light lists, else it loops over
 * every VPL. */
static void bind_gather(const gi_vpl *v, GLuint prog, int first_unit, int lists,
                        float absorption)
{
    const gl_functions *gl = v->gl;
    bind_texture(gl, prog, "u_vpls", GL_TEXTURE_2D, v->vpl_tex, first_unit + UNIT_VPLS);
    bind_texture(gl, prog, "u_vpl_shadow", GL_TEXTURE_2D_ARRAY, v->shadow_tex,
                 first_unit + UNIT_SHADOW);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_vpl_absorption"), absorption);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpl_count"), v->have_maps ? v->count : 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpl_visibility"), v->ism != NULL);
    if (v->ism)
        vpl_ism_bind(v->ism, prog, first_unit + UNIT_ISM);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpl_face"), v->face);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpl_tiles"), v->tiles);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_vpl_far"), v->far);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_vpl_face_axis"), VPL_FACES, FACE_AXIS[0]);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_vpl_face_right"), VPL_FACES, FACE_RIGHT[0]);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_vpl_face_up"), VPL_FACES, FACE_UP[0]);
    const vpl_grid *g = &v->grid;
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpl_clustered"), lists && v->grid_valid);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpl_list_row"), LIST_ROW);
    bind_texture(gl, prog, "u_vpl_cluster_first", GL_TEXTURE_2D, v->cluster_tex,
                 first_unit + UNIT_CLUSTERS);
    bind_texture(gl, prog, "u_vpl_cluster_index", GL_TEXTURE_2D, v->list_tex,
                 first_unit + UNIT_LISTS);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_vpl_grid_apex"), 1, g->apex);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_vpl_grid_right"), 1, g->right);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_vpl_grid_up"), 1, g->up);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_vpl_grid_forward"), 1, g->forward);
    gl->Uniform4fv(gl->GetUniformLocation(prog, "u_vpl_grid_window"), 1, g->window);
    gl->Uniform2f(gl->GetUniformLocation(prog, "u_vpl_grid_depth"), g->near,
                  v->grid_valid ? logf(g->far / g->near) : 1.0f);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_vpl_grid_size"), g->tiles[0], g->tiles[1],
                  g->slices);
}

/* Interleaved: the gather and blur run here (vpl_interleave.h) and the snippet reads them. */
static void eye_bind(void *state, const gi_eye *e)
{
    gi_vpl *v = state;
    if (e->view)
        eye_lists(v, e->view);
    const gl_functions *gl = v->gl;
    int interleaved = v->interleave && v->have_maps && v->count > 0;
    float absorption = v->reuse.last.absorption;
    if (interleaved) {
        GLuint g = vpl_interleave_program(v->interleave);
        gl->UseProgram(g);
        bind_gather(v, g, e->first_unit, 0, absorption);
        vpl_interleave_run(v->interleave, e, e->first_unit + UNIT_IRRADIANCE);
        gl->Uniform1i(gl->GetUniformLocation(e->program, "u_vpl_irradiance"),
                      e->first_unit + UNIT_IRRADIANCE);
    }
    bind_gather(v, e->program, e->first_unit, 1, absorption);
    gl->Uniform1i(gl->GetUniformLocation(e->program, "u_vpl_interleaved"), interleaved);
}

static void stats(const void *state, gi_stats *out)
{
    const gi_vpl *v = state;
    out->stage_count = 2;
    out->stage[0] = (gi_stat){"select", v->select_ms};
    out->stage[1] = (gi_stat){"shadow", v->shadow_ms};
    out->figure_count = 2;
    out->figure[0] = (gi_stat){"assign_ms", v->assign_ms};
    out->figure[1] = (gi_stat){"assignments", (double)v->assignments};
}

const gi_method gi_vpl_method = {
    .name = "vpl",
    .shade = {"vpl/vpl_gather.glsl", "vpl/vpl_shade.glsl"},
    .create = create,
    .destroy = destroy,
    .reuse = reuse,
    .frame = frame,
    .screen = screen,
    .eye_bind = eye_bind,
    .stats = stats,
};
